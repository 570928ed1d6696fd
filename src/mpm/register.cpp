#include "mpm/register.h"

#include <memory>

#include "mpm/mpm_analysis.h"

namespace mpm_lig::mpm {

void register_analyses(AnalysisRegistry& registry, materials::MaterialRegistry materials) {
  auto shared = std::make_shared<const materials::MaterialRegistry>(std::move(materials));
  registry.add("mpm", [shared](const CaseNode& root) { return make_analysis(root, *shared); });
}

}  // namespace mpm_lig::mpm
