#pragma once

#include <algorithm>
#include <cmath>

#include "core/tensor.h"

//! Small-strain pieces of a deformation increment in the first `d` axes (the plane of a 2D
//! packing, all three in 3D), shared by the predictions of QuietPoints and SteadyFlow and the
//! RVE's sub-step rule.
namespace mpm_lig::plane {

//! Trace over the first `d` axes.
inline double trace_d(const Mat3& a, int d) {
  double t = 0.0;
  for (int i = 0; i < d; ++i)
    t += a(i, i);
  return t;
}

inline Mat3 in_plane(const Mat3& a, int d) {
  Mat3 b = Mat3::Zero();
  b.topLeftCorner(d, d) = a.topLeftCorner(d, d);
  return b;
}

inline Mat3 identity_d(int d) {
  Mat3 b = Mat3::Zero();
  for (int i = 0; i < d; ++i)
    b(i, i) = 1.0;
  return b;
}

//! The small strain of `increment` split into volumetric and deviatoric parts.
struct StrainParts {
  Mat3 strain;
  double volumetric;
  Mat3 deviatoric;
};

inline StrainParts strain_parts(const Mat3& increment, int d) {
  const Mat3 inc = increment - Mat3::Identity();
  const Mat3 strain = in_plane(0.5 * (inc + inc.transpose()), d);
  const double volumetric = trace_d(strain, d);
  return {strain, volumetric, strain - (volumetric / d) * identity_d(d)};
}

//! Engineering shear strain γ = √2 |e| of a deviatoric strain e (γ of a simple shear).
inline double engineering_shear(const Mat3& deviatoric) {
  return std::sqrt(2.0) * deviatoric.norm();
}

//! |prediction - stress| / |stress|, the stress's size floored at `floor` [Pa] so that the
//! error of a prediction near zero stress stays finite.
inline double relative_error(const Mat3& prediction, const Mat3& stress, double floor) {
  return (prediction - stress).norm() / std::max(stress.norm(), floor);
}

//! The first-order rotation of `stress` by the spin of `increment`.
inline Mat3 spin_of(const Mat3& stress, const Mat3& increment, int d) {
  const Mat3 inc = increment - Mat3::Identity();
  const Mat3 omega = in_plane(0.5 * (inc - inc.transpose()), d);
  return omega * stress - stress * omega;
}

}  // namespace mpm_lig::plane
