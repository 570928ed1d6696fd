// Updates that continue the engine's run without its set-up (Rve::EngineRun::continued, behind
// rve.setup_every > 1; LIGGGHTS): they must follow the one long run they stand for, and an update
// after require_setup() must be the shipped update bit for bit.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "rve/rve.h"
#include "test_packing.h"
#include "test_rve_spec.h"

using namespace mpm_lig;

namespace {

constexpr int kUpdates = 10;
constexpr int kSteps = 40;
constexpr double kShearPerUpdate = 2e-4;
constexpr auto kContinued = rve::Rve::EngineRun::continued;

rve::RveSpec spec() {
  return test::parse_rve(test::small_rve_json());
}

class RveContinuedTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    packing_ = test::consolidated_packing(
        spec(), std::string(MPM_LIG_BINARY_DIR) + "/test_rve_continued_packing");
  }
  static std::unique_ptr<rve::Rve> clone() {
    return rve::Rve::from_restart(spec(), packing_, MPI_COMM_WORLD, "clone");
  }
  static Mat3 shear(double gamma) {
    Mat3 dF = Mat3::Identity();
    dF(0, 1) = gamma;
    return dF;
  }
  static std::string packing_;
};
std::string RveContinuedTest::packing_;

double stress_difference(rve::Rve& a, rve::Rve& b) {
  return (a.stress() - b.stress()).norm();
}

}  // namespace

// A simple shear at a constant rate in kUpdates updates: the box's tilt and the streaming
// velocities are linear in time, so the updates are one run of kUpdates × kSteps steps cut in
// pieces. Continued, they follow that run to round-off; each set-up of the shipped updates
// re-evaluates the contacts and advances their tangential history by one step, which moves the
// stress by far more.
TEST_F(RveContinuedTest, ContinuedUpdatesFollowTheOneRunTheyCut) {
  auto one_run = clone();
  one_run->deform(shear(kUpdates * kShearPerUpdate), kUpdates * kSteps);
  auto continued = clone();
  auto set_up = clone();
  for (int k = 0; k < kUpdates; ++k) {
    continued->deform(shear(kShearPerUpdate), kSteps, kContinued);
    set_up->deform(shear(kShearPerUpdate), kSteps);
  }
  const double p = mean_pressure(one_run->stress(), 2);
  EXPECT_LT((continued->box_matrix() - one_run->box_matrix()).norm(),
            1e-12 * one_run->box_matrix().norm());
  const double continued_off = stress_difference(*continued, *one_run);
  const double set_up_off = stress_difference(*set_up, *one_run);
  std::printf("|stress - one run's| / p: continued %.3g, set up every update %.3g\n",
              continued_off / p, set_up_off / p);
  EXPECT_LT(continued_off, 1e-6 * p) << "set-up every update: " << set_up_off / p << " p";
  EXPECT_GT(set_up_off, 100.0 * continued_off);
}

// With a set-up before every update the kept fix and require_setup() change nothing: the
// shipped arithmetic, bit for bit.
TEST_F(RveContinuedTest, SetUpBeforeEveryUpdateIsTheShippedUpdate) {
  auto shipped = clone();
  auto kept = clone();
  for (int k = 0; k < kUpdates; ++k) {
    kept->require_setup();
    shipped->deform(shear(kShearPerUpdate), kSteps);
    kept->deform(shear(kShearPerUpdate), kSteps, kContinued);
  }
  const Mat3 a = shipped->stress(), b = kept->stress();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_EQ(a(i, j), b(i, j));
}

// A checkpoint in the middle of continued updates: the clone from it and the original take the
// same next update (the original sets up after writing, as the clone must).
TEST_F(RveContinuedTest, CheckpointSetsUpOnBothSides) {
  auto original = clone();
  for (int k = 0; k < 3; ++k)
    original->deform(shear(kShearPerUpdate), kSteps, kContinued);
  const std::string file =
      std::string(MPM_LIG_BINARY_DIR) + "/test_rve_continued_packing/mid.restart";
  original->write_checkpoint(file);
  auto resumed = rve::Rve::from_checkpoint(spec(), file, MPI_COMM_WORLD, "resumed");
  resumed->restore(original->state());
  for (int k = 0; k < 3; ++k) {
    original->deform(shear(kShearPerUpdate), kSteps, kContinued);
    resumed->deform(shear(kShearPerUpdate), kSteps, kContinued);
  }
  const Mat3 a = original->stress(), b = resumed->stress();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_EQ(a(i, j), b(i, j));
}
