#include "io/summary.h"

#include "io/atomic_file.h"

namespace mpm_lig::io {

void write_json(const std::string& filename, const nlohmann::json& summary) {
  replace_file(filename, summary.dump(2) + '\n', ".partial");
}

}  // namespace mpm_lig::io
