#include "rve/script.h"

#include <sstream>
#include <stdexcept>

namespace mpm_lig::rve {
namespace {

std::string substitute(const std::string& line, const std::map<std::string, std::string>& values) {
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t open = line.find("${", pos);
    if (open == std::string::npos)
      break;
    const std::size_t close = line.find('}', open);
    if (close == std::string::npos)
      throw std::invalid_argument("unterminated ${ in template line: " + line);
    const std::string name = line.substr(open + 2, close - open - 2);
    const auto it = values.find(name);
    if (it == values.end())
      throw std::invalid_argument("template value '" + name + "' not provided");
    out += line.substr(pos, open - pos) + it->second;
    pos = close + 1;
  }
  return out + line.substr(pos);
}

}  // namespace

std::string render_template(const std::string& text,
                            const std::map<std::string, std::string>& values,
                            const std::set<std::string>& flags) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  bool keep = true;
  while (std::getline(in, line)) {
    if (line.rfind("#@if ", 0) == 0) {
      keep = flags.count(line.substr(5)) != 0;
      continue;
    }
    if (line.rfind("#@endif", 0) == 0) {
      keep = true;
      continue;
    }
    // Comments stay out of the engine (they are for the reader of the template).
    if (!keep || line.empty() || line[0] == '#')
      continue;
    out << substitute(line, values) << '\n';
  }
  return out.str();
}

}  // namespace mpm_lig::rve
