#include "materials/plastic.h"

#include <algorithm>
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

double VonMises::yield_stress(double kappa) const {
  return std::max(yield_stress_ - softening_.modulus * kappa, softening_.residual);
}

Mat3 VonMises::correct(std::size_t point, const Mat3& trial) {
  const Mat3 deviator = trial - (trial.trace() / 3.0) * Mat3::Identity();
  const double q = std::sqrt(1.5 * deviator.squaredNorm());
  const double kappa = state(point, 0);
  const double yield = yield_stress(kappa);
  if (q <= yield)
    return trial;
  // Radial return, Δε_q^p along the deviator, no volume change: q − 3G Δε = q_y(κ + Δε).
  // On the softening branch Δε = (q − q_y(κ)) / (3G − H) (the reader keeps H < 3G); where
  // that passes the residual value, the end of the step flows perfectly at q_r.
  const double three_g = 3.0 * elasticity().shear;
  double flow = (q - yield) / (three_g - softening_.modulus);
  double returned = yield_stress(kappa + flow);
  if (softening_.modulus > 0.0 && returned <= softening_.residual) {
    returned = softening_.residual;
    flow = (q - returned) / three_g;
  }
  add_plastic(point, flow, 0.0);
  return trial - (1.0 - returned / q) * deviator;
}

MohrCoulombStrength MohrCoulomb::strength(double kappa) const {
  if (!(softening_.plastic_strain > 0.0))
    return strength_;
  const double progress = std::min(kappa / softening_.plastic_strain, 1.0);
  MohrCoulombStrength softened = strength_;
  softened.friction += progress * (softening_.residual_friction - strength_.friction);
  softened.dilatancy += progress * (softening_.residual_dilatancy - strength_.dilatancy);
  return softened;
}

Mat3 MohrCoulomb::correct(std::size_t point, const Mat3& trial) {
  // The strength of the step's start (explicit in κ): the MPM's steps are small against the
  // softening range, and the return stays the exact perfectly plastic one.
  const MohrCoulombStrength now = strength(state(point, 0));
  // Most points of a footing analysis are elastic in a step: test before the full spectral
  // decomposition.
  if (now.admissible(principal_values(trial)))
    return trial;
  const Principal p = principal(trial);
  ReturnKind kind;
  const Vec3 returned = mohr_coulomb_return(p.values, elasticity(), now, &kind);
  if (kind == ReturnKind::elastic)
    return trial;
  accumulate(point, plastic_strain(p.values, returned, elasticity()));
  return with_principal_change(trial, p, returned - p.values);
}

}  // namespace mpm_lig::materials
