// The kinematics phase: the case chooses its operators, and volumetric smoothing (F-bar) gives
// every point of a cell the volume-weighted mean volume change of that cell, rescaling the
// in-plane part of its increment only, so that its rotation and out-of-plane part stay.
#include <cmath>

#include <gtest/gtest.h>

#include "mpm/kinematics.h"
#include "mpm/volumetric_smoothing.h"

namespace mpm_lig::mpm {
namespace {

using Vec2 = Eigen::Vector2d;

//! A point at `x` of volume `volume` (only what the operator reads).
void add_point(Particles<2>& particles, const Vec2& x, double volume) {
  particles.position.push_back(x);
  particles.volume.push_back(volume);
}

Mat3 increment(double xx, double yy, double xy, double yx) {
  Mat3 dF = Mat3::Identity();
  dF(0, 0) = xx;
  dF(1, 1) = yy;
  dF(0, 1) = xy;
  dF(1, 0) = yx;
  return dF;
}

TEST(Kinematics, TheCaseChoosesTheOperators) {
  MpmCase c;
  EXPECT_TRUE(kinematics_operators<2>(c).empty());
  c.volumetric_smoothing = true;
  const auto operators = kinematics_operators<3>(c);
  ASSERT_EQ(operators.size(), 1u);
  EXPECT_EQ(operators[0]->name(), "volumetric_smoothing");
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
