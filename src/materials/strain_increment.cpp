#include "materials/strain_increment.h"

#include <cmath>
#include <stdexcept>

namespace mpm_lig::materials {

StrainIncrement split_increment(const Mat3& dF) {
  // det dF <= 0: the step turned the point inside out; no strain measure makes sense.
  if (!(dF.determinant() > 0.0))
    throw std::runtime_error("deformation increment inverts the material point (det dF <= 0)");
  const Mat3 identity = Mat3::Identity();
  const Mat3 sum = dF + identity;
  const double det = sum.determinant();
  // det(dF + I) = 8 for no deformation; near zero only for a step that (almost) inverts.
  if (!(std::abs(det) > 1e-12))
    throw std::runtime_error("deformation increment inverts the material point");
  const Mat3 gradient = 2.0 * (dF - identity) * sum.inverse();
  const Mat3 half_spin = 0.25 * (gradient - gradient.transpose());
  StrainIncrement out;
  out.strain = 0.5 * (gradient + gradient.transpose());
  out.rotation = (identity - half_spin).inverse() * (identity + half_spin);
  return out;
}

}  // namespace mpm_lig::materials
