#include "mpm/point_fields.h"

#include <cmath>

namespace mpm_lig::mpm {

Mat3 hencky_strain(const Mat3& deformation) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(deformation * deformation.transpose());
  const Vec3 log_stretch = 0.5 * eig.eigenvalues().array().max(1e-300).log();
  return eig.eigenvectors() * log_stretch.asDiagonal() * eig.eigenvectors().transpose();
}

double deviatoric_strain(const Mat3& strain) {
  const Mat3 e = strain - (strain.trace() / 3.0) * Mat3::Identity();
  return std::sqrt(2.0 / 3.0 * e.cwiseProduct(e).sum());
}

}  // namespace mpm_lig::mpm
