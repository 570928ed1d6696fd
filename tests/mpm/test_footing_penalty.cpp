// The penalty contact of a rigid footing (docs/footing_contact.md): its force on single points
// against the closed form, and a collapse load that does not depend on the time step.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/tensor.h"
#include "mpm/driver.h"
#include "mpm/footing.h"
#include "mpm/grid.h"
#include "mpm/particles.h"
#include "support.h"

namespace mpm_lig::mpm {
namespace {

//! Points of half size 0.25 cells (h = 0.05 m) at the given centres.
Particles<2> points_at(const std::vector<Eigen::Vector2d>& centres) {
  Particles<2> p;
  for (const auto& x : centres) {
    p.position.push_back(x);
    p.half_length.push_back(Eigen::Vector2d::Constant(0.25));
    p.external_force.push_back(Eigen::Vector2d::Zero());
  }
  return p;
}

//! A rough penalty footing B = 0.2 m wide centred on x = `center`, base at 0.6 m.
Footing penalty_footing(double center) {
  Footing spec;
  spec.center = {center};
  spec.width = {0.2};
  spec.base = 0.6;
  spec.velocity = 0.5;
  spec.contact = Footing::Contact::penalty;
  return spec;
}

TEST(PenaltyFooting, PressesEachPointByItsOverlap) {
  // B = 0.2 m centred on x = 0.3, base at 0.6; stiffness 1 x 1e8 Pa per cell of overlap.
  const Grid<2> grid(Eigen::Vector2d(0, 0), Eigen::Vector2d(0.6, 0.7), {12, 14});
  Footing spec = penalty_footing(0.3);
  spec.penalty_edge_inset = false;  // the whole footprint: [0.2, 0.4]
  RigidFooting<2> footing(spec, grid);
  const Eigen::Vector2d cell(0.05, 0.05);
  const double k = 1e8, half = 0.0125;
  Particles<2> p = points_at({{0.3, 0.59},    // under the middle, 2.5 mm into the base
                              {0.395, 0.59},  // straddling the right edge: 17.5 mm under it
                              {0.41, 0.62},   // beside the right face, 2.5 mm into it
                              {0.3, 0.58}});  // below the base, not touching
  footing.press(p, cell, k);
  const double into = 0.59 + half - 0.6;
  EXPECT_NEAR(p.external_force[0][1], -k * into / 0.05 * 2 * half, 1e-6);
  EXPECT_NEAR(p.external_force[0][0], 0.0, 1e-9);  // anchored where it first touched
  EXPECT_NEAR(p.external_force[1][1], -k * into / 0.05 * (0.4 - (0.395 - half)), 1e-6);
  // Out through the side: the overlap 2.5 mm over the box's height above the base.
  EXPECT_NEAR(p.external_force[2][0], k * (0.4 - (0.41 - half)) / 0.05 * 2 * half, 1e-6);
  EXPECT_NEAR(p.external_force[2][1], 0.0, 1e-9);
  EXPECT_EQ(p.external_force[3], Eigen::Vector2d::Zero());
  EXPECT_NEAR(footing.load(), -(p.external_force[0][1] + p.external_force[1][1]), 1e-6);
  EXPECT_TRUE(std::isnan(footing.anchors()[3][0]));
  EXPECT_DOUBLE_EQ(footing.anchors()[0][0], 0.3);

  // The rough base holds the point where it first touched: 1 mm to the right, pulled back.
  p.position[0][0] += 0.001;
  for (auto& f : p.external_force)
    f.setZero();
  footing.press(p, cell, k);
  EXPECT_NEAR(p.external_force[0][0], -k * 0.001 / 0.05 * 2 * half, 1e-6);
  // Out of touch, the anchor goes: touching again, the point is held where it is then.
  p.position[0][1] = 0.5;
  footing.press(p, cell, k);
  EXPECT_TRUE(std::isnan(footing.anchors()[0][0]));

  // By default both edges (inside the mesh) are inset by half a cell: [0.225, 0.375]. The
  // point straddling 0.4 is then beside the pressed span, one straddling 0.375 pressed by
  // its part under it.
  spec.penalty_edge_inset = true;
  RigidFooting<2> inset(spec, grid);
  Particles<2> q = points_at({{0.395, 0.59}, {0.37, 0.59}});
  inset.press(q, cell, k);
  EXPECT_EQ(q.external_force[0], Eigen::Vector2d::Zero());
  EXPECT_NEAR(q.external_force[1][1], -k * into / 0.05 * (0.375 - (0.37 - half)), 1e-6);
}

TEST(PenaltyFooting, RoughBaseHoldsUpToItsFrictionAngle) {
  // δ = 20°: a point 2.5 mm into the base is held by its spring while the spring's pull stays
  // below tan δ × the normal force, and slides once it would pass it, its anchor following.
  const Grid<2> grid(Eigen::Vector2d(0, 0), Eigen::Vector2d(0.6, 0.7), {12, 14});
  Footing spec = penalty_footing(0.3);
  spec.interface_friction_deg = 20.0;
  RigidFooting<2> footing(spec, grid);
  const Eigen::Vector2d cell(0.05, 0.05);
  const double k = 1e8, half = 0.0125, into = 0.59 + half - 0.6;
  const double normal = k * into / 0.05 * 2 * half, limit = std::tan(20.0 * kDegree) * normal;
  Particles<2> p = points_at({{0.3, 0.59}});
  footing.press(p, cell, k);
  const auto pressed_after = [&](double dx) {
    p.position[0][0] += dx;
    p.external_force[0].setZero();
    footing.press(p, cell, k);
    return p.external_force[0];
  };
  // tan 20° × 2.5 mm = 0.91 mm of spring: 0.5 mm is held, 3 mm slides.
  EXPECT_NEAR(pressed_after(0.0005)[0], -k * 0.0005 / 0.05 * 2 * half, 1e-6);
  EXPECT_NEAR(pressed_after(0.0025)[0], -limit, 1e-6);
  EXPECT_NEAR(pressed_after(0.0)[1], -normal, 1e-6);
  EXPECT_NEAR(p.position[0][0] - footing.anchors()[0][0], std::tan(20.0 * kDegree) * into, 1e-12);
  // Back 0.5 mm: the spring unloads from the limit, held again where the point slid to.
  EXPECT_NEAR(pressed_after(-0.0005)[0],
              -k * (std::tan(20.0 * kDegree) * into - 0.0005) / 0.05 * 2 * half, 1e-6);
  // Without a friction angle (90°: the default) the same path is held all the way.
  spec.interface_friction_deg = 90.0;
  RigidFooting<2> adhesive(spec, grid);
  Particles<2> q = points_at({{0.3, 0.59}});
  adhesive.press(q, cell, k);
  q.position[0][0] += 0.003;
  q.external_force[0].setZero();
  adhesive.press(q, cell, k);
  EXPECT_NEAR(q.external_force[0][0], -k * 0.003 / 0.05 * 2 * half, 1e-6);
}

TEST(PenaltyFooting, AHalfModelsSymmetryFaceIsNoEdge) {
  // Centre on the mesh face x = 0 (a half model): the footprint [0, 0.1] is inset at 0.1
  // only, and a point at the face is pushed down, never out through the face.
  const Grid<2> grid(Eigen::Vector2d(0, 0), Eigen::Vector2d(0.6, 0.7), {12, 14});
  const Footing spec = penalty_footing(0.0);
  RigidFooting<2> footing(spec, grid);
  Particles<2> p = points_at({{0.0125, 0.64}, {0.07, 0.59}, {0.08, 0.59}});
  footing.press(p, Eigen::Vector2d(0.05, 0.05), 1e8);
  EXPECT_NEAR(p.external_force[0][0], 0.0, 1e-9);
  EXPECT_LT(p.external_force[0][1], 0.0);
  EXPECT_NEAR(p.external_force[1][1] / p.external_force[2][1], 0.0175 / 0.0075, 1e-9);
}

//! Mean footing pressure over 0.015 <= d/B <= 0.03 of `name` at the given CFL number.
double collapse_pressure(const std::string& name, double cfl) {
  MpmProblem c = testing::load_case(name, [&](nlohmann::json& j) {
    j["output"]["fields"] = false;
    j["analysis"]["time_step"]["cfl"] = cfl;
    j["analysis"]["end"]["time"] = 0.31;
  });
  double sum = 0.0;
  int n = 0;
  run_case<2>(std::move(c), "", [&](const Solver<2>& s) {
    const auto& f = s.footings().front();
    const double ratio = f.settlement() / 1.0;  // B = 1 m
    if (ratio >= 0.015 && ratio <= 0.03) {
      sum += f.load() / f.contact_area();
      ++n;
    }
  });
  EXPECT_GT(n, 10);
  return sum / n;
}

TEST(PenaltyFooting, PrandtlLoadDoesNotDependOnTheTimeStep) {
  // Rough penalty footing on Tresca soil: q_u = (2 + pi) c_u at any step; h = B/20 carries
  // +3.5 % (docs/footing_contact.md).
  const double qu = (2.0 + kPi) * 1.0e4;
  const double half = collapse_pressure("prandtl_tresca_penalty", 0.5);
  const double quarter = collapse_pressure("prandtl_tresca_penalty", 0.25);
  // The check can fail: the node contact's load moves with the step.
  const double nodes_half = collapse_pressure("prandtl_tresca", 0.5);
  const double nodes_quarter = collapse_pressure("prandtl_tresca", 0.25);
  std::printf("q_u / (2 + pi) c_u at CFL 0.5 / 0.25: penalty %.4f / %.4f, nodes %.4f / %.4f\n",
              half / qu, quarter / qu, nodes_half / qu, nodes_quarter / qu);
  EXPECT_NEAR(quarter / half, 1.0, 0.002);
  EXPECT_NEAR(half / qu, 1.0, 0.05);
  EXPECT_GT(std::abs(nodes_quarter / nodes_half - 1.0), 0.01);
}

}  // namespace
}  // namespace mpm_lig::mpm
