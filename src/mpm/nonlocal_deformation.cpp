#include "mpm/nonlocal_deformation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "mpm/point_bins.h"

namespace mpm_lig::mpm {
namespace {

//! ΔF = V R: log V and R.
struct Polar {
  Mat3 log_stretch;
  Mat3 rotation;
};

Polar left_polar(const Mat3& increment) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(increment * increment.transpose());
  const Vec3 squared = eigen.eigenvalues();
  const Mat3& axes = eigen.eigenvectors();
  const Vec3 log_values = 0.5 * squared.array().log().matrix();
  const Vec3 inverse_values = squared.array().rsqrt().matrix();
  Polar polar;
  polar.log_stretch = axes * log_values.asDiagonal() * axes.transpose();
  polar.rotation = axes * inverse_values.asDiagonal() * axes.transpose() * increment;
  return polar;
}

Mat3 symmetric_exp(const Mat3& log_stretch) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(log_stretch);
  const Vec3 values = eigen.eigenvalues().array().exp().matrix();
  return eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace

template <int D>
NonlocalDeformation<D>::NonlocalDeformation(double length, double nonlocal_weight)
    : sigma_(kernel_width(length)), cutoff_(3.0 * kernel_width(length)), weight_(nonlocal_weight) {
  if (!(length > 0.0) || !(nonlocal_weight >= 0.0))
    throw std::invalid_argument("NonlocalDeformation: length must be > 0, weight >= 0");
}

template <int D>
double NonlocalDeformation<D>::kernel_width(double length) {
  return length / (2.0 * std::sqrt(2.0 * std::log(2.0)));
}

template <int D>
void NonlocalDeformation<D>::apply(const KinematicsContext<D>& context,
                                   std::vector<Mat3>& increments) const {
  const Particles<D>& particles = context.particles;
  const Grid<D>& grid = context.grid;
  const std::size_t n = particles.size();
  std::vector<Polar> polar(n);
  PointBins<D> bins(grid, cutoff_);
  for (std::size_t p = 0; p < n; ++p) {
    polar[p] = left_polar(increments[p]);
    bins.add(p, particles.position[p]);
  }
  const double inverse_two_s2 = 1.0 / (2.0 * sigma_ * sigma_);
  const double cutoff2 = cutoff_ * cutoff_;
  for (std::size_t p = 0; p < n; ++p) {
    Mat3 sum = Mat3::Zero();
    double total = 0.0;
    for (const std::size_t box : bins.around(particles.position[p])) {
      for (const std::size_t q : bins.members(box)) {
        const double r2 =
            separation(grid, particles.position[p], particles.position[q]).squaredNorm();
        if (r2 > cutoff2)
          continue;
        const double w = std::exp(-r2 * inverse_two_s2) * particles.volume[q];
        sum += w * polar[q].log_stretch;
        total += w;
      }
    }
    const Mat3 mixed = (1.0 - weight_) * polar[p].log_stretch + (weight_ / total) * sum;
    increments[p] = symmetric_exp(mixed) * polar[p].rotation;
  }
}

template class NonlocalDeformation<2>;
template class NonlocalDeformation<3>;

}  // namespace mpm_lig::mpm
