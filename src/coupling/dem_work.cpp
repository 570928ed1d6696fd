#include "coupling/dem_work.h"

#include <algorithm>

namespace mpm_lig::coupling {

void DemWork::start(std::size_t points, double grains, int max_substeps,
                    double preparation_pressure) {
  grains_ = grains;
  max_substeps_ = max_substeps;
  low_stress_ = kLowStressFraction * preparation_pressure;
  work_.assign(points * kValues, 0.0);
}

void DemWork::add(std::size_t point, double substeps, double mean_stress, const Mat3& dF) {
  const double w = substeps * grains_;
  double* v = work_.data() + point * kValues;
  v[0] += w;
  if (max_substeps_ > 0 && substeps >= max_substeps_)
    v[1] += w;
  if (mean_stress < low_stress_)
    v[2] += w;
  if ((dF - Mat3::Identity()).norm() < kQuietStrain)
    v[3] += w;
}

double DemWork::sum(int k) const {
  double s = 0.0;
  for (std::size_t i = static_cast<std::size_t>(k); i < work_.size(); i += kValues)
    s += work_[i];
  return s;
}

void DemWork::restore_row(std::size_t point, const double* values) {
  std::copy(values, values + kValues, work_.begin() + point * kValues);
}

}  // namespace mpm_lig::coupling
