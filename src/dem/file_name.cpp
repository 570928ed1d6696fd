#include "dem/file_name.h"

#include <stdexcept>

namespace mpm_lig::dem {

std::string unusable_file_name(const std::string& name) {
  if (name.empty())
    return "an empty file name";
  for (const char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f)
      return "a control character (line break, tab, ...) in the file name";
    if (c == '"')
      return "a double quote (\") in the file name, which the DEM engine cannot take";
    if (c == '*' || c == '%')
      return std::string("'") + c +
             "' in the file name, which the DEM engine replaces by a step or processor number";
  }
  return "";
}

std::string quoted_file_name(const std::string& name) {
  const std::string problem = unusable_file_name(name);
  if (!problem.empty())
    throw std::invalid_argument("cannot give '" + name + "' to the DEM engine: " + problem);
  return '"' + name + '"';
}

}  // namespace mpm_lig::dem
