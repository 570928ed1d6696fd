#include "io/summary.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "io/checked_stream.h"

namespace mpm_lig::io {

void write_json(const std::string& filename, const nlohmann::json& summary) {
  const std::string partial = filename + ".partial";
  {
    std::ofstream out(partial);
    if (!out)
      throw std::runtime_error("cannot write '" + partial + "'");
    out << summary.dump(2) << '\n';
    close_checked(out, partial);
  }
  if (std::rename(partial.c_str(), filename.c_str()) != 0) {
    throw std::runtime_error("cannot rename '" + partial + "' to '" + filename + "'");
  }
}

}  // namespace mpm_lig::io
