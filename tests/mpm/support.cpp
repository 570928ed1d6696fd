#include "support.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/case_node.h"

namespace mpm_lig::mpm::testing {

const materials::MaterialRegistry& material_registry() {
  static const materials::MaterialRegistry registry = [] {
    materials::MaterialRegistry r;
    materials::register_materials(r);
    return r;
  }();
  return registry;
}

MpmProblem load_case(const std::string& name, const std::function<void(nlohmann::json&)>& edit) {
  const std::string path = std::string(MPM_LIG_SOURCE_DIR) + "/cases/mpm/" + name + ".json";
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot open " + path);
  nlohmann::json j = nlohmann::json::parse(in);
  if (edit)
    edit(j);
  const auto document = CaseDocument::parse(j.dump());
  const CaseNode root = document.root();
  root.child("analysis").choice("type", {"mpm"});
  MpmProblem c = read_case(root, material_registry());
  document.check_all_used();
  return c;
}

}  // namespace mpm_lig::mpm::testing
