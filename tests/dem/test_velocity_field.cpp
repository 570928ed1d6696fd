// Engine::add_velocity_field in LIGGGHTS does the arithmetic of the commands it stands for
// (`variable … atom`, `velocity all set … sum yes units box`, `velocity all zero linear`) in
// place: the grains' velocities, and the run after, the same bit for bit.
#include <gtest/gtest.h>

#include "dem/engine.h"
#include "dem/velocity_field.h"
#include "dem_scripts.h"

namespace mpm_lig::dem::test {
namespace {

std::unique_ptr<Engine> sheared_packing() {
  auto engine = periodic_packing("liggghts", "velocity field test", 0.1);
  engine->command("fix shear all deform 1 xy delta 0.002 remap v");
  engine->command("run 100");
  return engine;
}

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b,
                      const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  int differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    differing += a[k] != b[k];
  EXPECT_EQ(differing, 0) << what;
}

class VelocityField : public ::testing::TestWithParam<int> {};

TEST_P(VelocityField, InPlaceIsTheCommandsBitForBit) {
  const int dimension = GetParam();
  // Three terms in every row (a sum of two is the same in either order): the order of the
  // sums is part of what must match.
  Mat3 gradient;
  gradient << 1.3e-3, -2.7e-2, 3.3e-3,  //
      4.1e-3, -1.1e-3, -5.9e-3,         //
      2.2e-3, 6.1e-3, 7e-4;
  const Vec3 origin(-1.5e-4, 2.5e-4, 3.1e-4);
  auto by_commands = sheared_packing();
  auto in_place = sheared_packing();
  by_commands->commands(velocity_field_commands(gradient, origin, dimension, "field"));
  in_place->add_velocity_field(gradient, origin, dimension);
  const std::vector<double> v = in_place->gather_atoms("v", 3);
  double largest = 0.0;
  for (double c : v)
    largest = std::max(largest, std::abs(c));
  ASSERT_GT(largest, 1e-5) << "the field must move the grains";
  expect_same_bits(by_commands->gather_atoms("v", 3), v, "velocities");
  by_commands->command("run 50");
  in_place->command("run 50");
  expect_same_bits(by_commands->gather_atoms("x", 3), in_place->gather_atoms("x", 3),
                   "positions 50 steps later");
}

INSTANTIATE_TEST_SUITE_P(Dimensions, VelocityField, ::testing::Values(2, 3));

}  // namespace
}  // namespace mpm_lig::dem::test
