#pragma once

#include <array>
#include <cmath>

#include <Eigen/Dense>

namespace mpm_lig {

//! π, the one definition the code uses.
inline constexpr double kPi = 3.14159265358979323846;
//! One degree in radians.
inline constexpr double kDegree = kPi / 180.0;

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

//! Mean stress p (compression positive, as in soil mechanics) of a tension-positive σ:
//! -tr(σ)/3, or the in-plane mean -(σxx + σyy)/2 for a 2D (disc) packing's stress.
inline double mean_pressure(const Mat3& sigma, int dimension = 3) {
  return dimension == 2 ? -0.5 * (sigma(0, 0) + sigma(1, 1)) : -sigma.trace() / 3.0;
}

//! Deviatoric stress q: the von Mises sqrt(3/2 s:s), or for a 2D (disc) packing's stress the
//! in-plane Mohr-circle radius.
inline double deviatoric_stress(const Mat3& sigma, int dimension = 3) {
  if (dimension == 2)
    return std::hypot(0.5 * (sigma(0, 0) - sigma(1, 1)), sigma(0, 1));
  const Mat3 s = sigma - (sigma.trace() / 3.0) * Mat3::Identity();
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

//! The largest and smallest principal stresses {σ1, σ3}, compression positive, of a
//! tension-positive σ: in-plane for a 2D (disc) packing's stress.
inline std::array<double, 2> extreme_principal_stresses(const Mat3& sigma, int dimension = 3) {
  if (dimension == 2) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> e2(-sigma.topLeftCorner<2, 2>(),
                                                            Eigen::EigenvaluesOnly);
    return {e2.eigenvalues()(1), e2.eigenvalues()(0)};
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(-sigma, Eigen::EigenvaluesOnly);
  return {eig.eigenvalues()(2), eig.eigenvalues()(0)};  // ascending
}

//! Logarithmic (Hencky) strain ln V = ½ ln(F Fᵀ), tension positive. Principal stretches are
//! floored at 1e-300 so that a degenerate F gives a large finite strain, not -inf.
inline Mat3 hencky_strain(const Mat3& deformation) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(deformation * deformation.transpose());
  const Vec3 log_stretch = 0.5 * eig.eigenvalues().array().max(1e-300).log();
  return eig.eigenvectors() * log_stretch.asDiagonal() * eig.eigenvectors().transpose();
}

//! Deviatoric strain invariant ε_q = sqrt(2/3 e:e), e the deviatoric part of `strain`.
inline double deviatoric_strain(const Mat3& strain) {
  const Mat3 e = strain - (strain.trace() / 3.0) * Mat3::Identity();
  return std::sqrt(2.0 / 3.0 * e.cwiseProduct(e).sum());
}

}  // namespace mpm_lig
