// The engine's virial pressure tensor equals Σ b⊗f / V over contacts() (σ = −P), on a small
// dense periodic triclinic packing after some shearing (so tangential forces are present).
#include <gtest/gtest.h>

#include "dem/engine.h"
#include "dem_scripts.h"

namespace mpm_lig::dem::test {
namespace {

struct VirialCase {
  std::string engine;
  double tolerance;  // relative to the largest component (measured: agreement to 1e-13)
};

class VirialStress : public ::testing::TestWithParam<VirialCase> {};

TEST_P(VirialStress, PressureTensorIsContactSum) {
  const VirialCase& param = GetParam();
  auto engine = periodic_packing(param.engine, "virial test", 0.1);
  engine->command("fix shear all deform 1 xy delta 0.002 xz delta -0.001 remap x");
  engine->command("run 400");
  // contacts() evaluates forces at the current positions and velocities; the virial of the
  // last step used the mid-step velocities in the damping terms. A setup pass (`run 0`)
  // puts both on the same state.
  engine->command("run 0");

  const std::vector<double> pressure = engine->compute_vector("p", 6);
  const std::vector<Contact> contacts = engine->contacts();
  const double volume = engine->box().volume();
  Mat3 sum = Mat3::Zero();
  double tangential = 0.0;
  for (const Contact& c : contacts) {
    sum += c.branch * c.force.transpose() / volume;
    tangential += (c.force - c.force.dot(c.branch.normalized()) * c.branch.normalized()).norm();
  }
  ASSERT_GT(contacts.size(), 100u);
  EXPECT_GT(tangential, 0.0) << "no tangential forces: the test would not cover them";

  // Virial pressure P = -(1/V) Σ b⊗f_i with b = x_j - x_i, so σ = -P = Σ b⊗f_i / V.
  const Voigt6 sigma_contacts = to_voigt(sum);
  double largest = 0.0;
  for (double p : pressure)
    largest = std::max(largest, std::abs(p));
  ASSERT_GT(largest, 1e3);
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(-pressure[k], sigma_contacts[k], param.tolerance * largest)
        << "component " << kVoigtNames[k];
}

INSTANTIATE_TEST_SUITE_P(Engines, VirialStress,
                         ::testing::Values(VirialCase{"liggghts", 1e-10},
                                           VirialCase{"lammps", 1e-10}),
                         [](const auto& test) { return test.param.engine; });

}  // namespace
}  // namespace mpm_lig::dem::test
