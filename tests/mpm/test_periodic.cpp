// A mesh periodic along x (mesh.periodic): a rigid block that flies out through x+ comes
// back through x- unchanged, a vibrating one keeps its mass and momentum across the seam, and
// an elastic layer sheared by its top row alone carries the closed-form simple-shear state.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "mpm/constraints.h"
#include "mpm/driver.h"
#include "mpm/grid.h"
#include "support.h"

namespace mpm_lig::mpm {
namespace {

using Vec2 = Eigen::Vector2d;

class Periodic : public ::testing::TestWithParam<std::string> {};

//! The free-flight block on a mesh periodic along x, fast enough to cross the seam twice.
MpmProblem periodic_flight(const std::string& shape, bool rigid) {
  return testing::load_case("free_flight", [&](nlohmann::json& j) {
    j["analysis"]["shape_function"] = shape;
    j["analysis"]["end"]["steps"] = 800;
    j["mesh"]["periodic"] = {"x"};
    j["output"]["fields"] = false;
    auto& body = j["bodies"][0];
    body["velocity"] = {4.0, 0.2};
    if (rigid)
      body.erase("velocity_profile");
  });
}

TEST_P(Periodic, RigidBlockCrossesTheSeamUnchanged) {
  MpmProblem c = periodic_flight(GetParam(), true);
  const double length = c.spec.size[0];
  const Vec2 v(4.0, 0.2);
  double travelled = 0.0;
  run_case<2>(std::move(c), "", [&](const Solver<2>& s) {
    const auto& p = s.particles();
    for (std::size_t k = 0; k < p.size(); ++k) {
      ASSERT_GE(p.position[k][0], 0.0);
      ASSERT_LT(p.position[k][0], length);
      Vec2 drift = p.position[k] - p.reference[k] - v * s.time();
      drift[0] -= length * std::round(drift[0] / length);  // the seam moved it by whole L
      ASSERT_LT(drift.norm(), 1e-10);
      ASSERT_LT((p.velocity[k] - v).norm(), 1e-9 * v.norm());
      ASSERT_LT((p.deformation[k] - Mat3::Identity()).norm(), 1e-9);
    }
    travelled = v[0] * s.time();
  });
  EXPECT_GT(travelled, 1.5 * length);  // every point crossed the seam, some twice
}

TEST_P(Periodic, VibratingBlockKeepsMassAndMomentumAcrossTheSeam) {
  MpmProblem c = periodic_flight(GetParam(), false);
  double mass0 = -1.0;
  Vec2 momentum0 = Vec2::Zero();
  int seam_crossings = 0;
  std::vector<double> previous;
  run_case<2>(std::move(c), "", [&](const Solver<2>& s) {
    const auto& p = s.particles();
    double mass = 0.0;
    Vec2 momentum = Vec2::Zero();
    for (std::size_t k = 0; k < p.size(); ++k) {
      mass += p.mass[k];
      momentum += p.mass[k] * p.velocity[k];
      if (k < previous.size() && p.position[k][0] < previous[k] - 1.0)
        ++seam_crossings;
    }
    previous.resize(p.size());
    for (std::size_t k = 0; k < p.size(); ++k)
      previous[k] = p.position[k][0];
    if (mass0 < 0.0) {
      mass0 = mass;
      momentum0 = momentum;
    }
    ASSERT_EQ(mass, mass0);
    ASSERT_LT((momentum - momentum0).norm(), 1e-9 * momentum0.norm());
  });
  EXPECT_GT(seam_crossings, 0);
}

INSTANTIATE_TEST_SUITE_P(Shapes, Periodic, ::testing::Values("linear", "gimp"));

class PeriodicShear : public ::testing::TestWithParam<std::string> {};

TEST_P(PeriodicShear, LayerCarriesTheClosedFormSimpleShear) {
  MpmProblem c = testing::load_case("periodic_simple_shear", [&](nlohmann::json& j) {
    j["analysis"]["shape_function"] = GetParam();
    j["output"]["fields"] = false;
  });
  const double height = c.spec.size[1];
  const auto& top = c.spec.constraints[2];
  // Triangular pulse over half a period: the top row moved by v_max T / 4.
  const double gamma = top.velocity * top.function.time / 4.0 / height;
  const double e = 1.0e7, nu = 0.3, g = e / (2.0 * (1.0 + nu));
  const Solver<2>* last = nullptr;
  std::vector<Mat3> stress;
  std::vector<Vec2> displacement, reference;
  run_case<2>(std::move(c), "", [&](const Solver<2>& s) {
    last = &s;
    const auto& p = s.particles();
    stress = p.stress;
    displacement.resize(p.size());
    reference = p.reference;
    for (std::size_t k = 0; k < p.size(); ++k)
      displacement[k] = p.position[k] - p.reference[k];
  });
  ASSERT_NE(last, nullptr);
  double worst = 0.0, mean = 0.0;
  for (const Mat3& s : stress)
    mean += s(0, 1) / static_cast<double>(stress.size());
  for (const Mat3& s : stress)
    worst = std::max(worst, std::abs(s(0, 1) - g * gamma));
  std::printf("sigma_xy / (G gamma): mean %.5f, worst point deviation %.2e\n", mean / (g * gamma),
              worst / (g * gamma));
  EXPECT_NEAR(mean, g * gamma, 0.01 * g * gamma);
  EXPECT_LT(worst, 0.02 * g * gamma) << "sigma_xy not uniform: worst deviation " << worst;
  // Points at one height move alike, wherever they are along the periodic axis.
  for (std::size_t a = 0; a < reference.size(); ++a) {
    for (std::size_t b = a + 1; b < reference.size(); ++b) {
      if (std::abs(reference[a][1] - reference[b][1]) < 1e-9) {
        ASSERT_LT((displacement[a] - displacement[b]).norm(), 1e-9 * gamma * height);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, PeriodicShear, ::testing::Values("linear", "gimp"));

TEST(PeriodicConstraints, UpperFaceNodesActOnTheirLowerPartners) {
  const Grid<2> grid(Vec2(0.0, 0.0), Vec2(0.4, 0.8), {4, 8}, {true, false});
  const Grid<2> plain_grid(Vec2(0.0, 0.0), Vec2(0.4, 0.8), {4, 8});
  Constraint upper_column;  // the x = L column only: on a periodic mesh, the x = 0 one
  upper_column.nodes.box = {{0.4, 0.0}, {0.4, 0.8}};
  Constraint top_row;  // both seam nodes of the top row: one node after folding
  top_row.nodes.box = {{0.0, 0.8}, {0.4, 0.8}};
  const NodeConstraints<2> folded({upper_column, top_row}, grid);
  const NodeConstraints<2> plain({upper_column, top_row}, plain_grid);
  ASSERT_EQ(folded.nodes(0).size(), 9u);
  for (const long id : folded.nodes(0))
    EXPECT_EQ(grid.node_index(id)[0], 0) << "node " << id;
  for (const long id : plain.nodes(0))
    EXPECT_EQ(plain_grid.node_index(id)[0], 4) << "node " << id;
  EXPECT_EQ(plain.nodes(1).size(), 5u);
  EXPECT_EQ(folded.nodes(1).size(), 4u);
}

}  // namespace
}  // namespace mpm_lig::mpm
