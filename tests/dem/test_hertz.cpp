// Hertz contact of two equal spheres against the closed form, through the public Engine API.
#include <gtest/gtest.h>

#include <cmath>

#include "dem/engine.h"
#include "dem_scripts.h"

namespace mpm_lig::dem::test {
namespace {

class HertzContact : public ::testing::TestWithParam<std::string> {};

TEST_P(HertzContact, NormalForceMatchesClosedForm) {
  const Material material;
  const double radius = 0.005, overlap = 1.0e-4;
  Box box;
  box.lo = Vec3::Constant(-0.05);
  box.hi = Vec3::Constant(0.05);
  auto engine = create_engine(GetParam(), MPI_COMM_SELF, {"hertz test", ""});
  engine->commands(setup_script(GetParam(), box, false, material));
  engine->commands(grains_script(
      {{Vec3::Zero(), radius}, {Vec3(2 * radius - overlap, 0, 0), radius}}, material));
  engine->commands(dynamics_script(1e-7, "p"));
  engine->command("run 0");

  // Two equal spheres: E* = E / (2 (1 - ν²)), R* = R / 2, F = 4/3 E* √R* δ^1.5.
  const double e_star = material.young / (2.0 * (1.0 - material.poisson * material.poisson));
  const double expected = 4.0 / 3.0 * e_star * std::sqrt(radius / 2.0) * std::pow(overlap, 1.5);

  const std::vector<double> f = engine->gather_atoms("f", 3);
  ASSERT_EQ(f.size(), 6u);
  EXPECT_NEAR(f[0], -expected, 1e-10 * expected);  // grain 1 is pushed towards -x
  EXPECT_NEAR(f[3], expected, 1e-10 * expected);
  for (int k : {1, 2, 4, 5})
    EXPECT_EQ(f[k], 0.0);

  const std::vector<Contact> contacts = engine->contacts();
  ASSERT_EQ(contacts.size(), 1u);
  const Contact& c = contacts[0];
  const double sign = c.id_i == 1 ? 1.0 : -1.0;  // branch and force are seen from grain i
  EXPECT_EQ(c.id_i + c.id_j, 3);
  EXPECT_NEAR(c.branch.x(), sign * (2 * radius - overlap), 1e-15);
  EXPECT_NEAR(c.force.x(), -sign * expected, 1e-10 * expected);
  EXPECT_NEAR(c.branch.tail(2).norm() + c.force.tail(2).norm(), 0.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Engines, HertzContact, ::testing::Values("liggghts", "lammps"));

}  // namespace
}  // namespace mpm_lig::dem::test
