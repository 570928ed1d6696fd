#include "materials/continuum.h"

#include <stdexcept>
#include <string>

namespace mpm_lig::materials {

std::size_t ContinuumMaterial::add_points(std::size_t count) {
  const std::size_t first = stress_.size();
  stress_.resize(first + count, Mat3::Zero());
  resize_state(stress_.size());
  return first;
}

void ContinuumMaterial::set_stress(std::size_t point, const Mat3& sigma) {
  stress_.at(point) = 0.5 * (sigma + sigma.transpose());
}

void ContinuumMaterial::update(const MaterialStep& step, std::vector<Mat3>& stress) {
  const std::vector<std::size_t>& points = step.points;
  const std::vector<Mat3>& dF = step.dF;
  if (dF.size() != points.size())
    throw std::invalid_argument("material update: one deformation increment per point needed");
  stress.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::size_t p = points[k];
    if (p >= stress_.size())
      throw std::out_of_range("material update: point " + std::to_string(p) + " was never added");
    const StrainIncrement inc = split_increment(dF[k]);
    const Mat3 trial = rotated(stress_[p], inc.rotation) + elasticity_.stress(inc.strain);
    stress_[p] = correct(p, trial);
    stress[k] = stress_[p];
  }
}

}  // namespace mpm_lig::materials
