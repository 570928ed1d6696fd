#pragma once

#include <array>
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "materials/material.h"

namespace mpm_lig::materials::testing {

//! Rotation about a unit axis by an angle (radians).
inline Mat3 rotation(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

//! Advance one point of `m` by `dF` and return its stress.
inline Mat3 step(Material& m, std::size_t point, const Mat3& dF) {
  std::vector<Mat3> out;
  m.update({{point}, {dF}, 1.0}, out);
  return out[0];
}

//! Mixed control of one point: each group of diagonal increments dF_ii (i in `free[k]`,
//! moved together) is found so that σ_ii of the group's first axis stays at `target`; the
//! rest of dF is prescribed. Tie axes that symmetry makes equal (triaxial lateral axes): on
//! a yield-surface edge they cannot be told apart. Newton with a finite-difference Jacobian
//! on copies of the material (Law must be copyable).
template <class Law>
Mat3 mixed_step(Law& law, Mat3 dF, const std::vector<std::vector<int>>& free, const Vec3& target) {
  const int n = static_cast<int>(free.size());
  auto residual = [&](const Mat3& trial_dF) {
    Law copy = law;
    const Mat3 s = step(copy, 0, trial_dF);
    Eigen::VectorXd r(n);
    for (int k = 0; k < n; ++k)
      r[k] = s(free[k][0], free[k][0]) - target[free[k][0]];
    return r;
  };
  for (int iteration = 0; iteration < 20; ++iteration) {
    const Eigen::VectorXd r = residual(dF);
    if (r.cwiseAbs().maxCoeff() < 1e-10 * (target.cwiseAbs().maxCoeff() + 1.0))
      break;
    Eigen::MatrixXd jacobian(n, n);
    const double h = 1e-7;
    for (int k = 0; k < n; ++k) {
      Mat3 shifted = dF;
      for (const int i : free[k])
        shifted(i, i) += h;
      jacobian.col(k) = (residual(shifted) - r) / h;
    }
    const Eigen::VectorXd change = jacobian.partialPivLu().solve(-r);
    for (int k = 0; k < n; ++k)
      for (const int i : free[k])
        dF(i, i) += change[k];
  }
  return step(law, 0, dF);
}

//! Plane-strain simple shear at constant vertical stress σ_yy = −`vertical`, no horizontal
//! strain, from a K0 = 0.5 state: `steps` shear increments `dgamma`; returns the last stress.
template <class Law>
Mat3 simple_shear_at_constant_vertical_stress(Law& law, double vertical, int steps, double dgamma) {
  Mat3 k0 = -vertical * Mat3::Identity();
  k0(0, 0) = k0(2, 2) = -0.5 * vertical;
  law.set_stress(0, k0);
  Mat3 s;
  for (int i = 0; i < steps; ++i) {
    Mat3 dF = Mat3::Identity();
    dF(0, 1) = dgamma;
    s = mixed_step(law, dF, {{1}}, Vec3(0.0, -vertical, 0.0));
  }
  return s;
}

//! Drained triaxial compression along z from an isotropic state −`confining`, the lateral
//! stress held at −`confining`: `steps` axial strain increments `dstrain`.
template <class Law>
Mat3 triaxial_compression(Law& law, double confining, int steps, double dstrain) {
  law.set_stress(0, -confining * Mat3::Identity());
  Mat3 s;
  for (int i = 0; i < steps; ++i) {
    Mat3 dF = Mat3::Identity();
    dF(2, 2) = 1.0 - dstrain;
    s = mixed_step(law, dF, {{0, 1}}, Vec3(-confining, -confining, 0.0));
  }
  return s;
}

}  // namespace mpm_lig::materials::testing
