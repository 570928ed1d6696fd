// Free flight: a rigid translation is reproduced exactly; a vibrating block keeps its mass
// and momentum (no constraints, no gravity, no damping), in 2D and 3D, for both schemes.
#include <gtest/gtest.h>

#include "mpm/driver.h"
#include "support.h"

namespace mpm_lig::mpm {
namespace {

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
