#pragma once

#include <cstddef>
#include <vector>

#include "core/tensor.h"

namespace mpm_lig::coupling {

//! Where a DEM material's work goes: every point's cumulative particle-steps and the parts of
//! it spent at the sub-step cap, in packings at low mean stress and on points barely deforming
//! (the three places the inertial-number rule spends work that may change nothing).
class DemWork {
 public:
  //! A step's mean stress below this fraction of the preparation pressure counts as "low".
  static constexpr double kLowStressFraction = 0.1;
  //! A step whose |ΔF - 1| is below this counts as "quiet".
  static constexpr double kQuietStrain = 1e-5;
  //! Values per point in a checkpoint row (total, at max, low stress, quiet).
  static constexpr int kValues = 4;

  //! Nothing booked for `points` points of `grains` grains; `max_substeps` <= 0: no cap.
  void start(std::size_t points, double grains, int max_substeps, double preparation_pressure);
  //! Books one update of `point`: `substeps` DEM steps taken from a packing at mean stress
  //! `mean_stress` (compression positive, before the update) under the increment `dF`.
  void add(std::size_t point, double substeps, double mean_stress, const Mat3& dF);
  //! Cumulative particle-steps of `point`.
  double total(std::size_t point) const { return work_[point * kValues]; }
  //! Sum over the points of value k (0 total, 1 at max, 2 low stress, 3 quiet).
  double sum(int k) const;
  const double* row(std::size_t point) const { return work_.data() + point * kValues; }
  void restore_row(std::size_t point, const double* values);

 private:
  double grains_ = 0.0;
  int max_substeps_ = 0;
  double low_stress_ = 0.0;
  std::vector<double> work_;
};

}  // namespace mpm_lig::coupling
