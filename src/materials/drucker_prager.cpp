#include "materials/drucker_prager.h"

#include <cmath>

namespace mpm_lig::materials {
namespace {

//! η and ξ of a cone matched to friction angle `angle` (also used for η̄ with ψ).
void coefficients(DruckerPragerCone::Match match, double angle, double& eta, double& xi) {
  const double s = std::sin(angle);
  switch (match) {
    case DruckerPragerCone::Match::plane_strain: {
      const double t = std::tan(angle);
      const double root = std::sqrt(9.0 + 12.0 * t * t);
      eta = 3.0 * t / root;
      xi = 3.0 / root;
      return;
    }
    case DruckerPragerCone::Match::triaxial_compression:
      eta = 6.0 * s / (std::sqrt(3.0) * (3.0 - s));
      xi = 6.0 * std::cos(angle) / (std::sqrt(3.0) * (3.0 - s));
      return;
    case DruckerPragerCone::Match::triaxial_extension:
      eta = 6.0 * s / (std::sqrt(3.0) * (3.0 + s));
      xi = 6.0 * std::cos(angle) / (std::sqrt(3.0) * (3.0 + s));
      return;
  }
}

}  // namespace

DruckerPragerCone DruckerPragerCone::matched(Match match, double cohesion, double friction,
                                             double dilatancy) {
  DruckerPragerCone cone;
  double xi = 0.0, unused = 0.0;
  coefficients(match, friction, cone.eta, xi);
  coefficients(match, dilatancy, cone.eta_flow, unused);
  cone.xi_c = xi * cohesion;
  return cone;
}

Mat3 DruckerPrager::correct(std::size_t point, const Mat3& trial) {
  const Elasticity& e = elasticity();
  const double mean = trial.trace() / 3.0;
  const Mat3 deviator = trial - mean * Mat3::Identity();
  const double root_j2 = std::sqrt(0.5 * deviator.squaredNorm());
  const double f = root_j2 + cone_.eta * mean - cone_.xi_c;
  if (f <= 1e-12 * (std::abs(mean) + root_j2 + cone_.xi_c))
    return trial;
  // Cone: √J2 and σ_m move linearly with the multiplier; past the apex (√J2 < 0) the
  // return is the apex itself, σ = ξc/η I.
  const double gamma = f / (e.shear + e.bulk * cone_.eta * cone_.eta_flow);
  const double new_root_j2 = root_j2 - e.shear * gamma;
  Mat3 out;
  if (new_root_j2 >= 0.0 && root_j2 > 0.0) {
    out = (new_root_j2 / root_j2) * deviator +
          (mean - e.bulk * cone_.eta_flow * gamma) * Mat3::Identity();
  } else {
    out = (cone_.xi_c / cone_.eta) * Mat3::Identity();
  }
  const Mat3 change = trial - out;
  const double volumetric = change.trace() / (3.0 * e.bulk);
  const Mat3 deviatoric = (change - (change.trace() / 3.0) * Mat3::Identity()) / (2.0 * e.shear);
  add_plastic(point, std::sqrt(2.0 / 3.0 * deviatoric.squaredNorm()), volumetric);
  return out;
}

}  // namespace mpm_lig::materials
