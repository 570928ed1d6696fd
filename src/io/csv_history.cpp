#include "io/csv_history.h"

#include <cstdio>
#include <stdexcept>

#include "io/checked_stream.h"

namespace mpm_lig::io {

CsvHistory::CsvHistory(const std::string& filename, std::vector<std::string> columns, bool append)
    : columns_(std::move(columns)),
      filename_(filename),
      out_(filename, append ? std::ios::app : std::ios::trunc) {
  if (!out_)
    throw std::runtime_error("cannot write '" + filename + "'");
  if (append)
    return;
  out_ << header(columns_) << '\n';
  flush_checked(out_, filename_);
}

std::string CsvHistory::header(const std::vector<std::string>& columns) {
  std::string line;
  for (std::size_t i = 0; i < columns.size(); ++i)
    line += (i ? "," : "") + columns[i];
  return line;
}

void CsvHistory::write(const std::vector<double>& values) {
  if (values.size() != columns_.size()) {
    throw std::invalid_argument("history row has " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_.size()) + " columns");
  }
  char buffer[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    // 17 significant digits: rows round-trip exactly (resume and rank-count comparisons).
    std::snprintf(buffer, sizeof buffer, "%.17g", values[i]);
    out_ << (i ? "," : "") << buffer;
  }
  out_ << '\n';
  flush_checked(out_, filename_);
}

}  // namespace mpm_lig::io
