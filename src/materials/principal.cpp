#include "materials/principal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace mpm_lig::materials {
namespace {

//! Sort the three (value, vector) pairs by descending value.
Principal sorted(const Vec3& values, const Mat3& vectors) {
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values[a] > values[b]; });
  Principal p;
  for (int i = 0; i < 3; ++i) {
    p.values[i] = values[order[i]];
    p.vectors.col(i) = vectors.col(order[i]);
  }
  return p;
}

Principal plane(const Mat3& t) {
  const double mean = 0.5 * (t(0, 0) + t(1, 1));
  const double half_diff = 0.5 * (t(0, 0) - t(1, 1));
  const double radius = std::hypot(half_diff, t(0, 1));
  const double angle = 0.5 * std::atan2(t(0, 1), half_diff);
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Mat3 vectors;
  vectors << c, -s, 0.0,  //
      s, c, 0.0,          //
      0.0, 0.0, 1.0;
  return sorted(Vec3(mean + radius, mean - radius, t(2, 2)), vectors);
}

}  // namespace

Vec3 principal_values(const Mat3& t) {
  Vec3 values;
  if (t(0, 2) == 0.0 && t(1, 2) == 0.0) {
    const double mean = 0.5 * (t(0, 0) + t(1, 1));
    const double radius = std::hypot(0.5 * (t(0, 0) - t(1, 1)), t(0, 1));
    values = Vec3(mean + radius, mean - radius, t(2, 2));
  } else {
    Eigen::SelfAdjointEigenSolver<Mat3> solver;
    solver.computeDirect(t, Eigen::EigenvaluesOnly);
    values = solver.eigenvalues();
  }
  std::sort(values.data(), values.data() + 3, std::greater<double>());
  return values;
}

Principal principal(const Mat3& t) {
  if (t(0, 2) == 0.0 && t(1, 2) == 0.0)
    return plane(t);
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(t);
  return sorted(solver.eigenvalues(), solver.eigenvectors());
}

Mat3 with_principal_change(const Mat3& t, const Principal& p, const Vec3& change) {
  return t + p.vectors * change.asDiagonal() * p.vectors.transpose();
}

}  // namespace mpm_lig::materials
