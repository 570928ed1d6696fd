#include "materials/plastic.h"

#include <cmath>

#include "materials/principal.h"

namespace mpm_lig::materials {

double PlasticMaterial::state(std::size_t point, std::size_t k) const {
  return plastic_.at(point)[static_cast<Eigen::Index>(k)];
}

void PlasticMaterial::set_state(std::size_t point, std::size_t k, double value) {
  plastic_.at(point)[static_cast<Eigen::Index>(k)] = value;
}

void PlasticMaterial::accumulate(std::size_t point, const Vec3& plastic_principal) {
  const double volumetric = plastic_principal.sum();
  const Vec3 deviatoric = plastic_principal - (volumetric / 3.0) * Vec3::Ones();
  add_plastic(point, std::sqrt(2.0 / 3.0 * deviatoric.squaredNorm()), volumetric);
}

Mat3 VonMises::correct(std::size_t point, const Mat3& trial) {
  const Mat3 deviator = trial - (trial.trace() / 3.0) * Mat3::Identity();
  const double q = std::sqrt(1.5 * deviator.squaredNorm());
  if (q <= yield_stress_)
    return trial;
  const double shrink = yield_stress_ / q;
  // Radial return: Δε_q^p = (q − q_y) / 3G along the deviator, no volume change.
  add_plastic(point, (q - yield_stress_) / (3.0 * elasticity().shear), 0.0);
  return trial - (1.0 - shrink) * deviator;
}

Mat3 MohrCoulomb::correct(std::size_t point, const Mat3& trial) {
  // Most points of a footing analysis are elastic in a step: test before the full spectral
  // decomposition.
  if (strength_.admissible(principal_values(trial)))
    return trial;
  const Principal p = principal(trial);
  ReturnKind kind;
  const Vec3 returned = mohr_coulomb_return(p.values, elasticity(), strength_, &kind);
  if (kind == ReturnKind::elastic)
    return trial;
  accumulate(point, plastic_strain(p.values, returned, elasticity()));
  return with_principal_change(trial, p, returned - p.values);
}

}  // namespace mpm_lig::materials
