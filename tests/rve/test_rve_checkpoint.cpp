// A checkpoint leaves a running RVE's arithmetic untouched: after write_checkpoint the RVE goes
// on bit for bit as a twin that wrote none, and a clone read from the checkpoint does the same
// (docs/DESIGN.md §10). Sheared for 30 updates, any round-off difference shows in the stress.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "rve/rve.h"
#include "test_packing.h"
#include "test_rve_spec.h"

using namespace mpm_lig;

namespace {

Mat3 shear_increment(int k) {
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 2e-3 * (1.0 + 0.1 * (k % 3));
  dF(1, 1) = 1.0 - 5e-4;
  return dF;
}

void expect_bit_identical(const Mat3& a, const Mat3& b, const std::string& what) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_EQ(a(i, j), b(i, j)) << what << ", stress component " << i << j;
}

void check_checkpoint_is_free_of_effect(const std::string& engine) {
  nlohmann::json json = test::small_rve_json();
  json["engine"] = engine;
  json["substeps"] = {{"fixed", 30}};
  const rve::RveSpec spec = test::parse_rve(json);
  const std::string dir = std::string(MPM_LIG_BINARY_DIR) + "/test_rve_checkpoint_" + engine;
  const std::string packing = test::consolidated_packing(spec, dir);
  const std::string checkpoint = dir + "/point.restart";
  auto plain = rve::Rve::from_restart(spec, packing, MPI_COMM_WORLD, "plain");
  auto written = rve::Rve::from_restart(spec, packing, MPI_COMM_WORLD, "checkpointed");
  for (int k = 0; k < 5; ++k) {
    plain->deform(shear_increment(k));
    written->deform(shear_increment(k));
  }
  written->write_checkpoint(checkpoint);
  auto clone = rve::Rve::from_checkpoint(spec, checkpoint, MPI_COMM_WORLD, "clone");
  clone->restore(written->state());
  for (int k = 5; k < 35; ++k) {
    plain->deform(shear_increment(k));
    written->deform(shear_increment(k));
    clone->deform(shear_increment(k));
  }
  const Mat3 reference = plain->stress();
  ASSERT_GT(-reference.trace(), 0.0) << "the sheared packing carries no stress";
  expect_bit_identical(written->stress(), reference, engine + ": RVE that wrote a checkpoint");
  expect_bit_identical(clone->stress(), reference, engine + ": clone read from the checkpoint");
}

}  // namespace

TEST(RveCheckpoint, LeavesLiggghtsArithmeticUntouched) {
  check_checkpoint_is_free_of_effect("liggghts");
}

#ifdef MPM_LIG_TEST_LAMMPS
TEST(RveCheckpoint, LeavesLammpsArithmeticUntouched) {
  check_checkpoint_is_free_of_effect("lammps");
}
#endif
