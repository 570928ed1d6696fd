// Free flight: a rigid translation is reproduced exactly; a vibrating block keeps its mass
// and momentum (no constraints, no gravity, no damping), in 2D and 3D, for both schemes; the
// FLIP share of the velocity update on its first step.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/tensor.h"
#include "mpm/driver.h"
#include "support.h"

namespace mpm_lig::mpm {
namespace {

using Vec2 = Eigen::Vector2d;

struct Variant {
  int dimension;
  std::string shape;
  std::string scheme;
};

void PrintTo(const Variant& v, std::ostream* out) {
  *out << v.dimension << "D " << v.shape << " " << v.scheme;
}

std::string name_of(const ::testing::TestParamInfo<Variant>& info) {
  return std::to_string(info.param.dimension) + "d_" + info.param.shape + "_" + info.param.scheme;
}

//! The free-flight case, in 3D when asked (a slab in z), with the variant's scheme.
MpmProblem free_flight(const Variant& v, bool rigid) {
  return testing::load_case("free_flight", [&](nlohmann::json& j) {
    j["analysis"]["shape_function"] = v.shape;
    j["analysis"]["scheme"] = v.scheme;
    j["output"]["fields"] = false;
    auto& body = j["bodies"][0];
    if (rigid)
      body.erase("velocity_profile");
    if (v.dimension == 3) {
      j["dimension"] = 3;
      j["mesh"] = {{"origin", {0, 0, 0}}, {"size", {2.0, 1.0, 0.6}}, {"cells", {20, 10, 6}}};
      body["box"] = {{"min", {0.2, 0.2, 0.2}}, {"max", {0.6, 0.6, 0.4}}};
      body["velocity"] = {2.0, 0.5, -0.3};
      if (!rigid)
        body["velocity_profile"]["amplitude"] = {1.0, -0.5, 0.25};
      j["analysis"]["end"]["steps"] = 150;
    }
  });
}

class FreeFlight : public ::testing::TestWithParam<Variant> {};

template <int D>
void check_rigid_translation(MpmProblem c) {
  const Eigen::Matrix<double, D, 1> v =
      Eigen::Map<const Eigen::Matrix<double, D, 1>>(c.spec.bodies[0].velocity.data());
  double moved = 0.0;
  run_case<D>(std::move(c), "", [&](const Solver<D>& s) {
    const auto& p = s.particles();
    for (std::size_t k = 0; k < p.size(); ++k) {
      // Exact up to round-off (gradients of order 1/h summed over 4-27 nodes each step).
      ASSERT_LT((p.position[k] - p.reference[k] - v * s.time()).norm(), 1e-11);
      ASSERT_LT((p.velocity[k] - v).norm(), 1e-9 * v.norm());
      ASSERT_LT((p.deformation[k] - Mat3::Identity()).norm(), 1e-9);
      ASSERT_LT(p.stress[k].norm(), 1e-3);  // Pa, against E = 1 MPa
    }
    moved = (v * s.time()).norm();
  });
  EXPECT_GT(moved, 3.0 * 0.1);  // crossed several cells
}

TEST_P(FreeFlight, RigidTranslationIsExact) {
  if (GetParam().dimension == 2)
    check_rigid_translation<2>(free_flight(GetParam(), true));
  else
    check_rigid_translation<3>(free_flight(GetParam(), true));
}

template <int D>
void check_conservation(MpmProblem c) {
  double mass0 = -1.0;
  Eigen::Matrix<double, D, 1> momentum0;
  double max_strain = 0.0;
  run_case<D>(std::move(c), "", [&](const Solver<D>& s) {
    if (mass0 < 0.0) {
      mass0 = s.total_mass();
      momentum0 = s.total_momentum();
    }
    double grid_mass = 0.0;
    for (const double m : s.grid().mass)
      grid_mass += m;
    EXPECT_NEAR(grid_mass, mass0, 1e-12 * mass0);
    EXPECT_NEAR(s.total_mass(), mass0, 1e-14 * mass0);
    EXPECT_LT((s.total_momentum() - momentum0).norm(), 1e-10 * momentum0.norm());
    for (const auto& F : s.particles().deformation)
      max_strain = std::max(max_strain, (F - Mat3::Identity()).norm());
  });
  EXPECT_GT(max_strain, 1e-3);  // the block did deform: the check is not trivial
}

TEST_P(FreeFlight, MassAndMomentumAreConserved) {
  if (GetParam().dimension == 2)
    check_conservation<2>(free_flight(GetParam(), false));
  else
    check_conservation<3>(free_flight(GetParam(), false));
}

//! The velocities and positions of the free-flight block's points after its first step, with
//! the velocity update's FLIP share `flip`.
struct FirstStep {
  std::vector<Vec2> velocity, position, start_velocity;
  double time_step = 0.0;
};

FirstStep first_step(double flip, double gravity = 0.0) {
  MpmProblem c = testing::load_case("free_flight", [&](nlohmann::json& j) {
    j["analysis"]["flip"] = flip;
    if (gravity != 0.0)
      j["gravity"] = {0.0, -gravity};
    j["analysis"]["end"]["steps"] = 1;
    j["output"]["fields"] = false;
  });
  const Vec2 uniform(c.spec.bodies[0].velocity[0], c.spec.bodies[0].velocity[1]);
  const Vec2 amplitude(c.spec.bodies[0].profile_amplitude[0],
                       c.spec.bodies[0].profile_amplitude[1]);
  const double start = c.spec.bodies[0].profile_start, length = c.spec.bodies[0].profile_length;
  FirstStep out;
  run_case<2>(std::move(c), "", [&](const Solver<2>& s) {
    const auto& p = s.particles();
    for (std::size_t k = 0; k < p.size(); ++k) {
      out.velocity.push_back(p.velocity[k]);
      out.position.push_back(p.position[k]);
      // The body's initial velocity profile (a quarter sine along x), at the point's start.
      out.start_velocity.push_back(
          uniform + std::sin(0.5 * kPi * (p.reference[k][0] - start) / length) * amplitude);
    }
    out.time_step = s.time();
  });
  return out;
}

// In the first step nothing acts on the block (no stress yet, no gravity, no constraint):
// pure FLIP (flip 1) keeps every point's own velocity, PIC (flip 0) replaces it with the grid's,
// which smooths the profile, and flip 0.99 is the linear blend of the two. The points move with
// the grid's velocity whatever the share.
TEST(VelocityUpdate, FlipShareBlendsThePointsOwnVelocityWithTheGrids) {
  const FirstStep flip = first_step(1.0), pic = first_step(0.0), blend = first_step(0.99);
  ASSERT_EQ(flip.velocity.size(), pic.velocity.size());
  ASSERT_EQ(flip.velocity.size(), blend.velocity.size());
  double smoothed = 0.0;
  for (std::size_t k = 0; k < flip.velocity.size(); ++k) {
    EXPECT_LT((flip.velocity[k] - flip.start_velocity[k]).norm(), 1e-12) << "point " << k;
    smoothed = std::max(smoothed, (pic.velocity[k] - pic.start_velocity[k]).norm());
    EXPECT_LT((blend.velocity[k] - (0.99 * flip.velocity[k] + 0.01 * pic.velocity[k])).norm(),
              1e-12)
        << "point " << k;
    EXPECT_LT((blend.position[k] - flip.position[k]).norm(), 1e-15) << "point " << k;
    EXPECT_LT((pic.position[k] - flip.position[k]).norm(), 1e-15) << "point " << k;
  }
  // The grid does change the profile, so the checks above tell FLIP from PIC.
  EXPECT_GT(smoothed, 1e-2) << "largest change of a point's velocity under PIC: " << smoothed;
}

// Under gravity alone every node accelerates by g, so whatever the FLIP share every point's
// velocity after the first step is its force-free one plus g dt: the grid's increment enters
// once, in the FLIP part and in the PIC part alike.
TEST(VelocityUpdate, EveryFlipShareAddsTheGridsIncrementOnce) {
  constexpr double g = 9.81;
  for (const double flip : {1.0, 0.99, 0.0}) {
    const FirstStep still = first_step(flip), falling = first_step(flip, g);
    ASSERT_EQ(still.velocity.size(), falling.velocity.size());
    ASSERT_GT(falling.time_step, 0.0);
    const Vec2 increment(0.0, -g * falling.time_step);
    for (std::size_t k = 0; k < still.velocity.size(); ++k)
      ASSERT_LT((falling.velocity[k] - still.velocity[k] - increment).norm(), 1e-12 * g)
          << "flip " << flip << ", point " << k << ", g dt = " << g * falling.time_step;
  }
}

INSTANTIATE_TEST_SUITE_P(Variants, FreeFlight,
                         // No linear + USL: its nodes at the edge of the body get tiny masses but
                         // full-size gradients, and the run blows up (README, "MPM cases").
                         ::testing::Values(Variant{2, "linear", "musl"},
                                           Variant{3, "linear", "musl"}, Variant{2, "gimp", "musl"},
                                           Variant{2, "gimp", "usl"}, Variant{3, "gimp", "usl"},
                                           Variant{3, "gimp", "musl"}),
                         name_of);

}  // namespace
}  // namespace mpm_lig::mpm
