// The kinematics phase: the case chooses its operators, and volumetric smoothing (F-bar) gives
// every point of a cell the volume-weighted mean volume change of that cell, rescaling the
// in-plane part of its increment only, so that its rotation and out-of-plane part stay. The
// non-local operator (internal length) averages log-stretches with a Gaussian of the distance
// times the volume, across materials, nearest image across a periodic face, and keeps each
// point's own rotation.
#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "mpm/kinematics.h"
#include "mpm/nonlocal_deformation.h"
#include "mpm/volumetric_smoothing.h"
#include "support.h"

namespace mpm_lig::mpm {
namespace {

using testing::plane_rotation;

using Vec2 = Eigen::Vector2d;

//! A point at `x` of volume `volume` (only what the operator reads).
void add_point(Particles<2>& particles, const Vec2& x, double volume, int material = 0) {
  particles.position.push_back(x);
  particles.volume.push_back(volume);
  particles.material.push_back(material);
}

Mat3 increment(double xx, double yy, double xy, double yx) {
  Mat3 dF = Mat3::Identity();
  dF(0, 0) = xx;
  dF(1, 1) = yy;
  dF(0, 1) = xy;
  dF(1, 0) = yx;
  return dF;
}

//! A pure stretch diag(a, b, 1) and its logarithm.
Mat3 stretch(double a, double b) {
  return increment(a, b, 0.0, 0.0);
}
Mat3 log_of(const Mat3& diagonal) {
  Mat3 l = Mat3::Zero();
  for (int k = 0; k < 3; ++k)
    l(k, k) = std::log(diagonal(k, k));
  return l;
}

TEST(Kinematics, TheCaseChoosesTheOperators) {
  MpmCase c;
  EXPECT_TRUE(kinematics_operators<2>(c).empty());
  c.volumetric_smoothing = true;
  const auto operators = kinematics_operators<3>(c);
  ASSERT_EQ(operators.size(), 1u);
  EXPECT_EQ(operators[0]->name(), "volumetric_smoothing");
  c.internal_length = 0.1;  // by the second gradient (default): not a kinematics operator
  EXPECT_EQ(kinematics_operators<2>(c).size(), 1u);
  c.internal_length_method = "nonlocal";
  const auto both = kinematics_operators<2>(c);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0]->name(), "internal_length");  // the F-bar corrects the averaged increments
  EXPECT_EQ(both[1]->name(), "volumetric_smoothing");
}

TEST(Kinematics, NonlocalTakesTheKernelAndVolumeWeightedMeanOfLogStretch) {
  const double length = 0.2, s = NonlocalDeformation<2>::kernel_width(length);
  EXPECT_NEAR(2.0 * s * std::sqrt(2.0 * std::log(2.0)), length, 1e-15);  // ℓ = FWHM
  const Grid<2> grid(Vec2(0.0, 0.0), Vec2(2.0, 1.0), {20, 10});
  Particles<2> particles;
  add_point(particles, Vec2(0.5, 0.5), 1.0);
  add_point(particles, Vec2(0.6, 0.5), 2.0);             // r = 0.1
  add_point(particles, Vec2(0.5 - 3.01 * s, 0.5), 5.0);  // beyond the 3s cut
  add_point(particles, Vec2(0.5, 0.5 - 0.15), 7.0, 1);   // another material
  std::vector<Mat3> dF{stretch(1.01, 0.99), stretch(1.0, 1.02), stretch(1.1, 0.9),
                       stretch(0.9, 1.1)};
  const std::vector<Mat3> before = dF;
  NonlocalDeformation<2>(length, 1.0).apply({particles, grid, 1e-3}, dF);

  const double w1 = 2.0 * std::exp(-0.01 / (2.0 * s * s));
  const double w3 = 7.0 * std::exp(-0.0225 / (2.0 * s * s));  // the motion crosses materials
  const Mat3 mean =
      (1.0 * log_of(before[0]) + w1 * log_of(before[1]) + w3 * log_of(before[3])) / (1.0 + w1 + w3);
  EXPECT_NEAR((log_of(dF[0]) - mean).norm(), 0.0, 1e-14);
  EXPECT_NEAR(dF[0](0, 1), 0.0, 1e-15);
  // The point just beyond the cut from point 0 (and farther from the rest) keeps its own.
  EXPECT_NEAR((dF[2] - before[2]).norm(), 0.0, 1e-14);
}

TEST(Kinematics, NonlocalWeightMixesLocalAndMean) {
  const Grid<2> grid(Vec2(0.0, 0.0), Vec2(1.0, 1.0), {10, 10});
  Particles<2> particles;
  add_point(particles, Vec2(0.5, 0.5), 1.0);
  add_point(particles, Vec2(0.5, 0.5), 1.0);  // same place: the mean of the two
  const std::vector<Mat3> before{stretch(1.02, 1.0), stretch(1.0, 1.0)};
  const Mat3 mean = 0.5 * (log_of(before[0]) + log_of(before[1]));
  for (const double m : {0.0, 0.5, 1.5}) {
    std::vector<Mat3> dF = before;
    NonlocalDeformation<2>(0.1, m).apply({particles, grid, 1e-3}, dF);
    const Mat3 expected = (1.0 - m) * log_of(before[0]) + m * mean;
    EXPECT_NEAR((log_of(dF[0]) - expected).norm(), 0.0, 1e-14) << "m = " << m;
  }
}

TEST(Kinematics, NonlocalPassesRigidRotationsAndKeepsEachPointsOwnSpin) {
  const Grid<2> grid(Vec2(0.0, 0.0), Vec2(1.0, 1.0), {10, 10});
  Particles<2> particles;
  std::vector<Mat3> dF;
  for (int k = 0; k < 5; ++k) {
    add_point(particles, Vec2(0.4 + 0.03 * k, 0.5), 1.0 + k);
    dF.push_back(plane_rotation(0.3 * k - 0.5));  // a different rigid turn at every point
  }
  const std::vector<Mat3> before = dF;
  NonlocalDeformation<2>(0.2, 1.0).apply({particles, grid, 1e-3}, dF);
  for (int k = 0; k < 5; ++k)
    EXPECT_NEAR((dF[k] - before[k]).norm(), 0.0, 1e-14) << k;

  // A stretch under a spin: the stretch is averaged, each point keeps its rotation.
  std::vector<Mat3> turned{plane_rotation(0.2) * stretch(1.02, 0.98), plane_rotation(-0.4)};
  Particles<2> two;
  add_point(two, Vec2(0.5, 0.5), 1.0);
  add_point(two, Vec2(0.5, 0.5), 1.0);
  NonlocalDeformation<2>(0.2, 1.0).apply({two, grid, 1e-3}, turned);
  // V R = R (Rᵀ V R): the left stretch of R U is R U Rᵀ.
  const Mat3 v0 = plane_rotation(0.2) * stretch(1.02, 0.98) * plane_rotation(0.2).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> e(v0);
  const Mat3 log_v0 = e.eigenvectors() * e.eigenvalues().array().log().matrix().asDiagonal() *
                      e.eigenvectors().transpose();
  const Mat3 mean = 0.5 * log_v0;
  const Eigen::SelfAdjointEigenSolver<Mat3> m(mean);
  const Mat3 v_hat = m.eigenvectors() * m.eigenvalues().array().exp().matrix().asDiagonal() *
                     m.eigenvectors().transpose();
  EXPECT_NEAR((turned[0] - v_hat * plane_rotation(0.2)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((turned[1] - v_hat * plane_rotation(-0.4)).norm(), 0.0, 1e-14);
}

TEST(Kinematics, NonlocalReachesAcrossAPeriodicFaceByTheNearestImage) {
  const Grid<2> grid(Vec2(0.0, 0.0), Vec2(1.0, 1.0), {10, 10}, {true, false});
  Particles<2> particles;
  add_point(particles, Vec2(0.01, 0.5), 1.0);
  add_point(particles, Vec2(0.99, 0.5), 1.0);  // 0.02 away through the face
  std::vector<Mat3> dF{stretch(1.02, 1.0), stretch(1.0, 1.0)};
  const std::vector<Mat3> before = dF;
  const double length = 0.1, s = NonlocalDeformation<2>::kernel_width(length);
  NonlocalDeformation<2>(length, 1.0).apply({particles, grid, 1e-3}, dF);
  const double w = std::exp(-0.0004 / (2.0 * s * s));
  const Mat3 mean = (log_of(before[0]) + w * log_of(before[1])) / (1.0 + w);
  EXPECT_NEAR((log_of(dF[0]) - mean).norm(), 0.0, 1e-14);
}

TEST(Kinematics, VolumetricSmoothingTakesTheCellsVolumeWeightedMean) {
  const Grid<2> grid(Vec2(0.0, 0.0), Vec2(2.0, 1.0), {2, 1});
  Particles<2> particles;
  add_point(particles, Vec2(0.25, 0.5), 1.0);  // cell 0
  add_point(particles, Vec2(0.75, 0.5), 3.0);  // cell 0
  add_point(particles, Vec2(1.5, 0.5), 2.0);   // cell 1, alone
  std::vector<Mat3> dF{increment(1.01, 1.0, 0.0, 0.0), increment(1.0, 0.99, 0.002, -0.002),
                       increment(1.02, 0.995, 0.0, 0.001)};
  dF[1](2, 2) = 1.003;  // out of plane: kept
  const std::vector<Mat3> before = dF;
  VolumetricSmoothing<2>().apply({particles, grid, 1e-3}, dF);

  const double j_bar = (1.0 * before[0].determinant() + 3.0 * before[1].determinant()) / 4.0;
  for (int p = 0; p < 2; ++p) {
    const double in_plane = dF[p].topLeftCorner<2, 2>().determinant();
    EXPECT_NEAR(in_plane * dF[p](2, 2), j_bar, 1e-15) << p;
    // One factor on the in-plane block: its shape (and its spin) is the point's own.
    const double scale = dF[p](0, 0) / before[p](0, 0);
    EXPECT_NEAR((dF[p].topLeftCorner<2, 2>() - scale * before[p].topLeftCorner<2, 2>()).norm(), 0.0,
                1e-15)
        << p;
    EXPECT_EQ(dF[p](2, 2), before[p](2, 2)) << p;
  }
  EXPECT_NEAR((dF[2] - before[2]).norm(), 0.0, 1e-15);  // a cell of one point keeps its own
}

}  // namespace
}  // namespace mpm_lig::mpm
