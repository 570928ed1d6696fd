#pragma once

#include <array>

#include <Eigen/Dense>

namespace mpm_lig {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;
//! Six stress or strain components in Voigt order xx, yy, zz, xy, xz, yz (the LAMMPS
//! pressure order). Strain components are tensor (not engineering) shear components.
using Voigt6 = std::array<double, 6>;

//! Voigt component names in order, for CSV headers ("xx", "yy", ...).
inline constexpr std::array<const char*, 6> kVoigtNames = {"xx", "yy", "zz", "xy", "xz", "yz"};

inline Voigt6 to_voigt(const Mat3& t) {
  return {t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(0, 2), t(1, 2)};
}

inline Mat3 from_voigt(const Voigt6& v) {
  Mat3 t;
  t << v[0], v[3], v[4],  //
      v[3], v[1], v[5],   //
      v[4], v[5], v[2];
  return t;
}

//! Mean stress p = -tr(σ)/3 (compression positive, as in soil mechanics) for a tension-positive σ.
inline double mean_pressure(const Mat3& sigma) {
  return -sigma.trace() / 3.0;
}

//! Deviatoric (von Mises) stress q = sqrt(3/2 s:s).
inline double deviatoric_stress(const Mat3& sigma) {
  const Mat3 s = sigma - (sigma.trace() / 3.0) * Mat3::Identity();
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

}  // namespace mpm_lig
