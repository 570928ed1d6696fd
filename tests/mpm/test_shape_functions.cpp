// Shape functions: partition of unity, of its gradient, and linear reproduction, for every
// registered kind, at points all over a cell (cell faces included); and the grid's blind spot
// with one point per cell (the odd-even mode of docs/methods.md §7).
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mpm/shape_function.h"

namespace mpm_lig::mpm {
namespace {

constexpr double kCell = 0.25;

class ShapeKinds : public ::testing::TestWithParam<std::string> {};

TEST_P(ShapeKinds, PartitionOfUnityAndLinearReproduction) {
  const auto shape = shape_registry().create(GetParam());
  for (const double lp : {0.25, 1.0 / 6.0, 0.5}) {
    for (int k = 0; k <= 400; ++k) {
      const double xi = 3.0 + k / 400.0 * 1.0;  // one cell, both faces
      const Weights1d w = shape->weights(xi, lp, kCell);
      double sum = 0.0, slope = 0.0, x = 0.0, dx = 0.0;
      for (int a = 0; a < w.count; ++a) {
        EXPECT_GE(w.value[a], -1e-15);
        const double node_x = (w.first + a) * kCell;
        sum += w.value[a];
        slope += w.gradient[a];
        x += w.value[a] * node_x;
        dx += w.gradient[a] * node_x;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "xi " << xi << " lp " << lp;
      EXPECT_NEAR(slope, 0.0, 1e-12) << "xi " << xi << " lp " << lp;
      EXPECT_NEAR(x, xi * kCell, 1e-14) << "xi " << xi << " lp " << lp;
      EXPECT_NEAR(dx, 1.0, 1e-12) << "xi " << xi << " lp " << lp;
    }
  }
}

TEST(Gimp, GradientIsContinuousAcrossCellFaces) {
  // The reason for GIMP: no jump of the gradient when a point crosses a cell face.
  const GimpShape gimp;
  const double lp = 0.25, eps = 1e-9;
  const Weights1d left = gimp.weights(3.0 - eps, lp, kCell);
  const Weights1d right = gimp.weights(3.0 + eps, lp, kCell);
  for (int node = 1; node <= 4; ++node) {
    auto gradient_at = [&](const Weights1d& w) {
      const int a = node - w.first;
      return a >= 0 && a < w.count ? w.gradient[a] : 0.0;
    };
    EXPECT_NEAR(gradient_at(left), gradient_at(right), 1e-6) << "node " << node;
  }
  const LinearShape linear;
  EXPECT_GT(std::abs(linear.weights(3.0 - eps, lp, kCell).gradient[1] -
                     linear.weights(3.0 + eps, lp, kCell).gradient[0]),
            1.0);
}

//! The velocities Σ_i N_i(x_p) v_i of points `per_cell` a cell at their regular places (half
//! length 1 / (2 per_cell) cells) on a grid whose node velocities alternate, v_i = ±1: the
//! grid's shortest wave as its points see it.
std::vector<double> points_velocity_of_alternation(const ShapeFunction1d& shape, int per_cell) {
  constexpr int kCells = 12;
  std::vector<double> velocity;
  for (int p = per_cell; p < (kCells - 1) * per_cell; ++p) {  // away from the ends
    const Weights1d w = shape.weights((p + 0.5) / per_cell, 0.5 / per_cell, kCell);
    double v = 0.0;
    for (int a = 0; a < w.count; ++a)
      v += w.value[a] * ((w.first + a) % 2 ? 1.0 : -1.0);
    velocity.push_back(v);
  }
  return velocity;
}

TEST_P(ShapeKinds, OnePointPerCellDoesNotSeeTheGridsShortestWave) {
  // Each point at a cell's centre takes half of each of its two nodes: a node velocity
  // alternating from node to node moves no point, so that motion has no mass and is not
  // carried from one step to the next; with two points a cell the points see half of it.
  const auto shape = shape_registry().create(GetParam());
  for (const double v : points_velocity_of_alternation(*shape, 1))
    EXPECT_NEAR(v, 0.0, 1e-15);
  for (const double v : points_velocity_of_alternation(*shape, 2))
    EXPECT_GT(std::abs(v), 0.2);
}

INSTANTIATE_TEST_SUITE_P(AllKinds, ShapeKinds, ::testing::Values("linear", "gimp"));

}  // namespace
}  // namespace mpm_lig::mpm
