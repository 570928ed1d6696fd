// RVE checks on small consolidated packings (LIGGGHTS unless named): consolidation accuracy,
// rigid rotation, large simple shear with cell flips, clones, and Σ r⊗f / V.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "core/case_node.h"
#include "rve/consolidation.h"
#include "rve/kinematics.h"
#include "rve/rve.h"
#include "test_rve_spec.h"

using namespace mpm_lig;

namespace {

constexpr double kPressure = 1e5;

rve::RveSpec make_spec(const std::string& engine, int dimension, int grains) {
  nlohmann::json rve = test::small_rve_json();
  rve["engine"] = engine;
  rve["dimension"] = dimension;
  rve["grains"] = grains;
  return test::parse_rve(rve);
}

Mat3 rotation_z(double angle) {
  Mat3 r = Mat3::Identity();
  r(0, 0) = r(1, 1) = std::cos(angle);
  r(0, 1) = -std::sin(angle);
  r(1, 0) = std::sin(angle);
  return r;
}

//! One consolidated 2D packing shared by the tests (restart file), made once.
class RveTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    spec_ = std::make_unique<rve::RveSpec>(make_spec("liggghts", 2, 120));
    original_ = rve::Rve::generate(*spec_, MPI_COMM_WORLD, "test RVE");
    result_ = rve::consolidate(*original_);
    restart_ = std::string(MPM_LIG_BINARY_DIR) + "/test_rve_prepared.restart";
    original_->write_restart(restart_);
  }
  static void TearDownTestSuite() { original_.reset(); }
  std::unique_ptr<rve::Rve> clone() {
    return rve::Rve::from_restart(*spec_, restart_, MPI_COMM_WORLD, "clone");
  }
  //! A clone of 120 grains whose sub-step rule is `substeps`, its stress read (the rule reads
  //! the last measured mean stress).
  std::unique_ptr<rve::Rve> clone_stepping(const nlohmann::json& substeps) {
    nlohmann::json json = test::small_rve_json();
    json["grains"] = 120;
    json["substeps"] = substeps;
    auto r = rve::Rve::from_restart(test::parse_rve(json), restart_, MPI_COMM_WORLD, "clone");
    r->stress();
    return r;
  }
  static std::unique_ptr<rve::RveSpec> spec_;
  static std::unique_ptr<rve::Rve> original_;
  static rve::ConsolidationResult result_;
  static std::string restart_;
};
std::unique_ptr<rve::RveSpec> RveTest::spec_;
std::unique_ptr<rve::Rve> RveTest::original_;
rve::ConsolidationResult RveTest::result_;
std::string RveTest::restart_;

}  // namespace

TEST_F(RveTest, ConsolidationReachesTargetPressureAtRest) {
  const double p = mean_pressure(result_.final.stress, 2);
  EXPECT_NEAR(p, kPressure, 0.02 * kPressure);
  EXPECT_LT(result_.final.kinetic_ratio(), 0.01);
  // Isotropic: the deviator is small against p for a consolidated packing.
  EXPECT_LT(deviatoric_stress(result_.final.stress, 2), 0.1 * p);
  EXPECT_GT(result_.final.coordination_number, 2.5);
  // The clone reads the state back (a restart re-evaluates the contact forces once).
  auto c = clone();
  const Mat3 s = c->stress();
  EXPECT_LT((s - result_.final.stress).norm(), 1e-3 * kPressure);
}

TEST_F(RveTest, RigidRotationRotatesStressAndKeepsInvariants) {
  for (double total_deg : {90.0, 360.0}) {
    auto r = clone();
    auto still = clone();  // the same packing left alone for as many steps (slow creep)
    const int increments = static_cast<int>(total_deg / 5.0);
    const double step = total_deg / increments * kPi / 180.0;
    for (int k = 0; k < increments; ++k) {
      r->deform(rotation_z(step), 20);
      still->relax(20);
    }
    const Mat3 s0 = still->stress();
    const Mat3 s = r->stress();
    const Mat3 q = rotation_z(total_deg * kPi / 180.0);
    const Mat3 expected = q * s0 * q.transpose();
    const double p0 = mean_pressure(s0, 2);
    EXPECT_NEAR(mean_pressure(s, 2), p0, 0.01 * p0) << total_deg;
    EXPECT_NEAR(deviatoric_stress(s, 2), deviatoric_stress(s0, 2), 0.01 * p0) << total_deg;
    EXPECT_LT((s - expected).norm(), 0.01 * p0) << total_deg << "\n" << s << "\n" << expected;
    // The box itself never rotated: the rotation lives outside it.
    EXPECT_LT((r->box_matrix() - clone()->box_matrix()).norm(), 1e-9);
  }
}

TEST_F(RveTest, SimpleShearToHundredPercentFlipsTheCellAndLosesNothing) {
  auto r = clone();
  const double increment = 0.01;
  for (int k = 0; k < 100; ++k) {
    Mat3 dF = Mat3::Identity();
    dF(0, 1) = increment;
    r->deform(dF, 60);
  }
  const rve::Observables o = r->observe();
  EXPECT_EQ(o.grains, spec_->grains);
  EXPECT_TRUE(o.stress.allFinite());
  EXPECT_NO_THROW(r->check_health(o));
  const Mat3 h = r->box_matrix();
  EXPECT_LE(std::abs(h(0, 1)), 0.5 * h(0, 0) + 0.02 * h(1, 1));  // the cell basis was reduced
  EXPECT_GT(mean_pressure(o.stress, 2), 0.0);                    // still a packing under load
}

TEST_F(RveTest, CloneIsBitIdenticalToItsOriginalAfterTheSameDeformation) {
  rve::Rve* a = original_.get();
  auto b = clone();
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 2e-3;
  dF(1, 1) = 1.0 - 1e-3;
  for (int k = 0; k < 5; ++k) {
    a->deform(dF, 40);
    b->deform(dF, 40);
  }
  const Mat3 sa = a->stress(), sb = b->stress();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_EQ(sa(i, j), sb(i, j));
}

// rve.cell_angle_deg turns the packing as a whole: the turned clone answers ΔF as the plain
// clone answers the same increment seen in the cell's frame, Rᵀ ΔF R, its stress turned by R.
TEST_F(RveTest, CellAngleTurnsThePackingWithItsResponse) {
  const double angle = 30.0 * kDegree;
  nlohmann::json json = test::small_rve_json();
  json["grains"] = 120;
  json["cell_angle_deg"] = 30.0;
  auto turned = rve::Rve::from_restart(test::parse_rve(json), restart_, MPI_COMM_WORLD, "turned");
  auto plain = clone();
  const Mat3 q = rotation_z(angle);
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 2e-3;
  dF(1, 1) = 1.0 - 1e-3;
  for (int k = 0; k < 5; ++k) {
    turned->deform(dF, 40);
    plain->deform(q.transpose() * dF * q, 40);
  }
  const Mat3 s_turned = turned->stress(), s_plain = plain->stress();
  const double p = mean_pressure(s_plain, 2);
  EXPECT_LT((s_turned - q * s_plain * q.transpose()).norm(), 1e-6 * p)
      << s_turned << "\n"
      << q * s_plain * q.transpose();
  // Not trivially so: the sheared packing's stress differs from the unturned one's.
  EXPECT_GT((s_turned - s_plain).norm(), 0.02 * p);
  EXPECT_LT((turned->rotation() - q).norm(), 0.05);  // the turn, and the increments' spin
}

// The sub-step rule counts the mean stress as at least substeps.pressure_floor: a floor above
// the packing's pressure p asks for sqrt(p / floor) of the sub-steps (to the rounding up).
TEST_F(RveTest, PressureFloorBoundsSubsteps) {
  nlohmann::json substeps = {{"inertial_number", 1e-4}, {"min", 1}};
  auto a = clone_stepping(substeps);
  substeps["pressure_floor"] = 100 * kPressure;
  auto b = clone_stepping(substeps);
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 2e-3;
  const int n_plain = a->deform(dF), n_floored = b->deform(dF);
  EXPECT_GT(n_plain, 20);
  EXPECT_NEAR(n_floored, std::ceil(n_plain / 10.0), 1.0) << n_plain << " vs " << n_floored;
}

// γ = √2 |dev ε| is the engineering shear strain of a simple shear and 2e of a pure shear
// diag(e, -e); a uniform expansion has none, and a 2D RVE ignores the out-of-plane row.
TEST(ShearOfStrain, ClosedForms) {
  Mat3 simple = Mat3::Zero();
  simple(0, 1) = simple(1, 0) = 1.5e-3;
  EXPECT_NEAR(rve::shear_of_strain(simple, 2), 3e-3, 1e-15);
  EXPECT_NEAR(rve::shear_of_strain(simple, 3), 3e-3, 1e-15);
  const Mat3 pure = Vec3(2e-3, -2e-3, 0.0).asDiagonal();
  EXPECT_NEAR(rve::shear_of_strain(pure, 2), 4e-3, 1e-15);
  EXPECT_NEAR(rve::shear_of_strain(Mat3::Identity() * 0.01, 3), 0.0, 1e-15);
  const Mat3 expansion = Vec3(0.01, 0.01, 0.0).asDiagonal();
  EXPECT_NEAR(rve::shear_of_strain(expansion, 2), 0.0, 1e-15);
  EXPECT_GT(rve::shear_of_strain(expansion, 3), 0.0);
}

// Once the net shear strain it has run reaches substeps.sheared.shear_strain, an RVE steps at
// the sheared inertial number: the same sub-steps as the plain rule before (same packing, same
// increments, bit-identical stress), a third of them after (I 1e-4 -> 3e-4). Increments that
// reverse cancel: a packing shaken back and forth stays at the plain rule.
TEST_F(RveTest, ShearedPaceTakesOverAtItsNetShear) {
  nlohmann::json substeps = {{"inertial_number", 1e-4}, {"min", 1}};
  auto a = clone_stepping(substeps);
  substeps["sheared"] = {{"shear_strain", 5e-3}, {"inertial_number", 3e-4}};
  auto b = clone_stepping(substeps);
  auto shaken = clone_stepping(substeps);
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 2e-3;
  for (int k = 0; k < 3; ++k) {  // net shear 0, 2e-3, 4e-3 before each increment: the plain rule
    EXPECT_EQ(a->deform(dF), b->deform(dF)) << "increment " << k;
    const Mat3 sa = a->stress(), sb = b->stress();
    EXPECT_EQ((sa - sb).norm(), 0.0) << "increment " << k;
    shaken->deform(k % 2 ? dF.inverse() : dF);
  }
  EXPECT_NEAR(b->net_shear(), 6e-3, 1e-4);
  EXPECT_LT(shaken->net_shear(), 2.1e-3);
  const int n_plain = a->deform(dF), n_paced = b->deform(dF);
  EXPECT_GT(n_plain, 20);
  EXPECT_NEAR(n_paced, n_plain / 3.0, 0.15 * n_plain) << n_plain << " vs " << n_paced;
  EXPECT_EQ(rve::shear_of_strain(b->state().strain, 2), b->net_shear());
}

// Right after a run under `fix deform` (what an MPM update reads), with a reduced cell basis.
TEST_F(RveTest, HealthObservationMatchesTheFullOneAfterDeforming) {
  auto r = clone();
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 0.05;
  dF(0, 0) = 1.0 - 2e-3;
  for (int k = 0; k < 12; ++k)
    r->deform(dF, 40);
  test::expect_health_matches_full(*r, 0.01);  // 1.25e-3 shear per step, cells ~10 radii
}

TEST_F(RveTest, StressEqualsContactSumAfterDeformation) {
  auto r = clone();
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 3e-3;
  dF(0, 0) = 1.0 - 2e-3;
  r->deform(dF, 100);
  r->engine().command("run 0");  // virial and contact list of the same force evaluation
  const Mat3 s = r->stress();
  const Mat3 from_contacts = rve::contact_stress(r->engine().contacts(), r->volume());
  const Voigt6 a = to_voigt(s), b = to_voigt(from_contacts);  // upper components
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(a[i], b[i], 1e-6 * s.norm()) << kVoigtNames[i];
}

TEST(RveKinematics, QrSplitKeepsRotationOutsideTheBox) {
  Mat3 h;
  h << 0.1, 0.02, 0.01, 0, 0.09, -0.03, 0, 0, 0.11;
  Mat3 dF = rotation_z(0.3);
  dF(0, 1) += 0.05;
  const rve::BoxStep step = rve::box_step(dF, h);
  EXPECT_LT((step.rotation * step.target - dF * h).norm(), 1e-14);
  EXPECT_LT((step.rotation.transpose() * step.rotation - Mat3::Identity()).norm(), 1e-14);
  for (int i = 0; i < 3; ++i)
    EXPECT_GT(step.target(i, i), 0.0);
  EXPECT_NEAR(step.target(1, 0) + step.target(2, 0) + step.target(2, 1), 0.0, 1e-15);
  // A lattice-preserving basis reduction keeps the volume and bounds the tilts.
  Mat3 skew = h;
  skew(0, 1) = 0.17;
  const Mat3 reduced = rve::reduce_tilts(skew);
  EXPECT_NEAR(reduced.determinant(), skew.determinant(), 1e-16);
  EXPECT_LE(std::abs(reduced(0, 1)), 0.5 * reduced(0, 0));
}

// 3D with streaming velocities (the 3D default): rotation about an oblique axis.
TEST(RveStreaming, RigidRotationAboutObliqueAxisGivesNoSpuriousStress) {
  const rve::RveSpec spec = make_spec("liggghts", 3, 100);
  ASSERT_TRUE(spec.stream_velocity);
  auto r = rve::Rve::generate(spec, MPI_COMM_WORLD, "3D RVE");
  rve::consolidate(*r);
  const std::string file = std::string(MPM_LIG_BINARY_DIR) + "/test_rve_3d.restart";
  r->write_restart(file);
  auto still = rve::Rve::from_restart(spec, file, MPI_COMM_WORLD, "still");
  const Vec3 axis = Vec3(1.0, 2.0, 3.0).normalized();
  const int increments = 18;
  const Mat3 step = Eigen::AngleAxisd(kPi / 2 / increments, axis).toRotationMatrix();
  for (int k = 0; k < increments; ++k) {
    r->deform(step, 20);
    still->relax(20);
  }
  const Mat3 q = Eigen::AngleAxisd(kPi / 2, axis).toRotationMatrix();
  const Mat3 s0 = still->stress(), s = r->stress();
  const double p0 = mean_pressure(s0, 3);
  EXPECT_NEAR(mean_pressure(s, 3), p0, 0.01 * p0);
  EXPECT_NEAR(deviatoric_stress(s, 3), deviatoric_stress(s0, 3), 0.01 * p0);
  EXPECT_LT((s - q * s0 * q.transpose()).norm(), 0.01 * p0);
}
