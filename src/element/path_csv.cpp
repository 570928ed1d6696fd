#include "element/path_csv.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

namespace mpm_lig::element {
namespace {

//! The nine components in row-major order; the first four of kPlane are a plane path's.
constexpr std::array<const char*, 9> kComponent = {"F11", "F12", "F13", "F21", "F22",
                                                   "F23", "F31", "F32", "F33"};
constexpr std::array<int, 4> kPlane = {0, 1, 3, 4};  // F11 F12 F21 F22

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos)
    return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.push_back(trimmed(line.substr(start, comma - start)));
    if (comma == std::string::npos)
      return out;
    start = comma + 1;
  }
}

//! Where each column sits in a row (-1: absent).
struct Layout {
  int time = -1;
  int substeps = -1;
  int mean_stress = -1;  //!< column p
  std::array<int, 9> component;
  bool full = false;  //!< all nine components (else the plane four)
  std::size_t columns = 0;
};

Layout read_header(const std::vector<std::string>& names, const std::string& where) {
  Layout layout;
  layout.component.fill(-1);
  layout.columns = names.size();
  std::map<std::string, int*> known = {
      {"time", &layout.time}, {"substeps", &layout.substeps}, {"p", &layout.mean_stress}};
  for (int c = 0; c < 9; ++c)
    known[kComponent[c]] = &layout.component[c];
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto it = known.find(names[k]);
    if (it == known.end())
      throw PathFileError(where + ": unknown column '" + names[k] +
                          "' (columns: time, F11, F12, F21, F22 [, F13, F23, F31, F32, F33] "
                          "[, substeps] [, p])");
    if (*it->second >= 0)
      throw PathFileError(where + ": column '" + names[k] + "' appears twice");
    *it->second = static_cast<int>(k);
  }
  for (int c = 0; c < 9; ++c)
    layout.full = layout.full || (layout.component[c] >= 0 &&
                                  std::find(kPlane.begin(), kPlane.end(), c) == kPlane.end());
  std::string missing = layout.time < 0 ? "time" : "";
  for (int c = 0; c < 9; ++c) {
    const bool wanted = layout.full || std::find(kPlane.begin(), kPlane.end(), c) != kPlane.end();
    if (wanted && layout.component[c] < 0)
      missing += std::string(missing.empty() ? "" : ", ") + kComponent[c];
  }
  if (!missing.empty())
    throw PathFileError(where + ": missing column" +
                        (missing.find(',') == std::string::npos ? " " : "s ") + missing +
                        (layout.full ? " (a 3D path needs all nine F components)" : ""));
  return layout;
}

double number(const std::string& text, const std::string& where, const std::string& column) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE)
    throw PathFileError(where + ": " + column + " is '" + text + "', not a number");
  return value;
}

}  // namespace

RecordedPath read_path_csv(const std::string& file) {
  if (!std::filesystem::is_regular_file(file))
    throw PathFileError("no such file '" + file + "'");
  std::ifstream in(file);
  if (!in)
    throw PathFileError("cannot read '" + file + "'");
  RecordedPath path;
  path.source = file;
  std::optional<Layout> layout;
  std::string line;
  for (long number_of_line = 1; std::getline(in, line); ++number_of_line) {
    const std::string text = trimmed(line);
    if (text.empty() || text[0] == '#')
      continue;
    if (text.find('\0') != std::string::npos)
      throw PathFileError("'" + file + "' line " + std::to_string(number_of_line) +
                          ": not a text file");
    if (!layout) {
      layout = read_header(fields(text), "'" + file + "' line " + std::to_string(number_of_line));
      continue;
    }
    const std::string label = "row " + std::to_string(path.F.size() + 1) + " (line " +
                              std::to_string(number_of_line) + ")";
    const std::string where = "'" + file + "' " + label;
    const std::vector<std::string> values = fields(text);
    if (values.size() != layout->columns)
      throw PathFileError(where + ": " + std::to_string(values.size()) + " values for " +
                          std::to_string(layout->columns) + " columns");
    Mat3 F = Mat3::Identity();
    for (int c = 0; c < 9; ++c)
      if (layout->component[c] >= 0)
        F(c / 3, c % 3) = number(values[layout->component[c]], where, kComponent[c]);
    path.label.push_back(label);
    path.time.push_back(number(values[layout->time], where, "time"));
    path.F.push_back(F);
    if (layout->mean_stress >= 0)
      path.mean_stress.push_back(number(values[layout->mean_stress], where, "p"));
    if (layout->substeps >= 0) {
      const double n = number(values[layout->substeps], where, "substeps");
      if (!(n >= 0.0 && n <= 1e9 && n == std::floor(n)))
        throw PathFileError(where + ": substeps is " + values[layout->substeps] +
                            ", must be a whole number >= 0 (0: the RVE's sub-stepping rule)");
      if (path.F.size() > 1)
        path.substeps.push_back(static_cast<int>(n));
    } else if (path.F.size() > 1) {
      path.substeps.push_back(0);
    }
  }
  if (in.bad())
    throw PathFileError("cannot read '" + file + "'");
  if (!layout)
    throw PathFileError("'" + file + "' has no header row");
  path.recorded_increment.assign(path.intervals(), std::nullopt);
  return path;
}

}  // namespace mpm_lig::element
