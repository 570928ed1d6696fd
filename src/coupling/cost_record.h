#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace mpm_lig::coupling {

//! The per-point, per-update cost of a dem_rve material's run: `cost_record.h5` in the
//! material's folder of the output (written by rank 0; read by tools/scaling_model.py).
//!
//! One row per MPM update: `update` and `groups` (1-D), and per point (rows × points)
//! `predicted_steps` and `measured_steps` (DEM steps, 0 when the point ran none: quiet or
//! continuum), `seconds` (the owner's time in the point's update) and `group` (the rank group
//! that ran it). Attributes `grains` and `update_cost_steps` turn steps into particle-steps
//! the way the balancer does: (steps + update_cost_steps) × grains for a point that ran;
//! `floor_steps` is the fewest sub-steps an update takes (the part of a cost that persists).
//! Chunked and compressed; rows are buffered and appended by flush().
class CostRecord {
 public:
  CostRecord(std::string file, std::size_t points, double grains, double update_cost_steps,
             double floor_steps);
  ~CostRecord();
  CostRecord(const CostRecord&) = delete;
  CostRecord& operator=(const CostRecord&) = delete;

  //! Start a new file (an existing one is replaced).
  void create();
  //! Continue the file of a resumed run: rows after `update` are dropped; a missing or
  //! unreadable file is started again (its earlier rows are lost: the run goes on).
  void continue_after(long update);
  void add(long update, int groups, const std::vector<double>& predicted_steps,
           const std::vector<double>& measured_steps, const std::vector<double>& seconds,
           const std::vector<int>& group);
  //! Append the buffered rows to the file; throws naming the file when it cannot.
  void flush();
  std::size_t buffered() const { return update_.size(); }
  const std::string& file() const { return file_; }

 private:
  void clear_rows();

  std::string file_;
  std::size_t points_;
  double grains_;
  double update_cost_steps_;
  double floor_steps_;
  std::vector<long long> update_;
  std::vector<int> groups_;
  std::vector<int> predicted_, measured_, group_;
  std::vector<float> seconds_;
};

}  // namespace mpm_lig::coupling
