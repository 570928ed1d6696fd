#pragma once

#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpm_lig::io {

//! A problem with a FieldWriter file read back by read_point_history: missing or damaged file,
//! no steps, a missing dataset, a point it does not hold. The message names the file and the
//! step group; the caller adds where the file name came from (a case key).
class PointHistoryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! The point asked for is not in the file (the message says how many it holds).
class UnknownPointError : public PointHistoryError {
 public:
  using PointHistoryError::PointHistoryError;
};

//! One material point's values over every output step of a FieldWriter file (results.h5),
//! in step order.
struct PointHistory {
  std::size_t points = 0;          //!< points of the file's steps (all steps hold as many)
  std::vector<std::string> group;  //!< per step: its HDF5 group ("step_000120")
  std::vector<long> step;          //!< per step: its "step" attribute
  std::vector<double> time;        //!< per step: its "time" attribute
  //! Per field asked for: per step the point's row (empty where an optional field is absent).
  std::map<std::string, std::vector<std::vector<double>>> rows;
};

//! Row `point` of the datasets `required` (every step must hold them) and `optional` (taken
//! where present) of every step of `h5_path`, with each step's time and number. Reads only
//! that row of each dataset. Throws UnknownPointError for a point the file does not hold and
//! PointHistoryError for anything else; HDF5's own diagnostics stay quiet.
PointHistory read_point_history(const std::string& h5_path, std::size_t point,
                                const std::vector<std::string>& required,
                                const std::vector<std::string>& optional = {});

}  // namespace mpm_lig::io
