#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace mpm_lig::io {

//! A CSV time history: a header row, then one row of numbers per call, flushed each row
//! so that a killed run keeps everything it wrote.
class CsvHistory {
 public:
  CsvHistory(const std::string& filename, std::vector<std::string> columns, bool append = false);

  const std::vector<std::string>& columns() const { return columns_; }
  //! The header row (without its newline) for `columns`, as the file holds it.
  static std::string header(const std::vector<std::string>& columns);
  //! Write one row; throws std::invalid_argument if the count does not match the header and
  //! std::runtime_error if the row did not reach the file.
  void write(const std::vector<double>& values);

 private:
  std::vector<std::string> columns_;
  std::string filename_;
  std::ofstream out_;
};

}  // namespace mpm_lig::io
