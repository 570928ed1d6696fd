#pragma once

#include <stdexcept>
#include <string>

#include "element/recorded_path.h"

namespace mpm_lig::element {

//! A recorded-path CSV file that cannot be read as one: the message names the file, the line
//! and the column.
class PathFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Reads a recorded path from CSV (docs/case_reference.md §4): a header row, then one row per
//! recorded state. Columns, in any order: `time`; `F11, F12, F21, F22` (a plane path, F33 = 1)
//! or all nine `F11 … F33` (F_ij = ∂x_i/∂X_j, axes 1 2 3 = x y z); optionally `substeps`
//! (DEM steps of the interval that ends at the row, 0 for the RVE's rule; the first row's is not
//! used). Lines starting with '#' and blank lines are skipped. Checks the layout and that every
//! value is a number; the values themselves are checked by read_recorded_path.
RecordedPath read_path_csv(const std::string& file);

}  // namespace mpm_lig::element
