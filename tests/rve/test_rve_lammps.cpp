// The homogenised stress of a deformed LAMMPS RVE equals Σ r⊗f / V over its contacts, in 3D
// (spheres) and 2D (discs), and a 2D LAMMPS packing consolidates like a LIGGGHTS one.
#include <gtest/gtest.h>

#include <string>

#include "core/case_node.h"
#include "rve/consolidation.h"
#include "rve/rve.h"
#include "test_rve_spec.h"

using namespace mpm_lig;

namespace {

rve::RveSpec lammps_spec(int dimension) {
  nlohmann::json rve = test::small_rve_json();
  rve["engine"] = "lammps";
  rve["dimension"] = dimension;
  rve["seed"] = 5;
  return test::parse_rve(rve);
}

//! Compress a fresh packing until it carries load, shear it, compare the engine's virial
//! with the contact sum of the same force evaluation.
void expect_stress_equals_contact_sum(int dimension) {
  const rve::RveSpec spec = lammps_spec(dimension);
  auto r = rve::Rve::generate(spec, MPI_COMM_WORLD, "lammps RVE");
  Mat3 dF = Mat3::Identity() * (1.0 - 2e-3);
  if (dimension == 2)
    dF(2, 2) = 1.0;
  for (int k = 0; k < 400 && mean_pressure(r->stress(), dimension) < 2e4; ++k)
    r->deform(dF, 50);
  Mat3 shear = Mat3::Identity();
  shear(0, dimension - 1) = 2e-3;
  r->deform(shear, 100);
  r->engine().command("run 0");  // virial and contact list of the same force evaluation
  const Mat3 s = r->stress();
  ASSERT_GT(mean_pressure(s, dimension), 1e3);
  const auto contacts = r->engine().contacts();
  ASSERT_GT(contacts.size(), static_cast<std::size_t>(spec.grains / 2));
  const Mat3 from_contacts = rve::contact_stress(contacts, r->volume());
  const Voigt6 a = to_voigt(s), b = to_voigt(from_contacts);  // upper components
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(a[i], b[i], 1e-6 * s.norm()) << kVoigtNames[i];
}

}  // namespace

TEST(RveLammps, StressEqualsContactSumAfterDeformation3d) {
  expect_stress_equals_contact_sum(3);
}

TEST(RveLammps, StressEqualsContactSumAfterDeformation2d) {
  expect_stress_equals_contact_sum(2);
}

// Consolidation reads contacts after every servo run: right after `fix deform` changed the
// cell, when the engine's periodic images still sit in the previous step's cell.
TEST(RveLammps, ConsolidatesIn2dAndReadsContactsRightAfterDeforming) {
  const rve::RveSpec spec = lammps_spec(2);
  auto r = rve::Rve::generate(spec, MPI_COMM_WORLD, "lammps RVE");
  const rve::ConsolidationResult c = rve::consolidate(*r);
  const double p = mean_pressure(c.final.stress, 2);
  EXPECT_NEAR(p, 1e5, 0.02 * 1e5);
  EXPECT_LT(c.final.kinetic_ratio(), 0.01);
  EXPECT_GT(c.final.coordination_number, 2.5);
  // Without a `run 0`: the contact sum differs from the last step's virial only by that
  // step's change (damping velocities, one step of deformation).
  const Mat3 from_contacts = rve::contact_stress(r->engine().contacts(), r->volume());
  EXPECT_LT((from_contacts - r->stress()).norm(), 0.01 * p);
  test::expect_health_matches_full(*r, 0.0);  // after contacts()' set-up: no lag
}
