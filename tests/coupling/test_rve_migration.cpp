// A moved RVE (coupling::send_rve on the old owner, receive_rve on the new one) keeps its
// contact history and its exact placement: sheared on after the move it stays bit-identical to
// a twin that never moved, in its stress, its contact forces (the tangential part is the
// history: lost, it restarts from zero and the forces differ at once) and its grain positions.
// A control shows that the comparison sees a lost placement: the same moment saved and read
// back without it (Rve::from_restart) leaves the twin within the 32 updates.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "../rve/test_packing.h"
#include "../rve/test_rve_spec.h"
#include "coupling/rve_migration.h"
#include "rve/placement.h"
#include "rve/rve.h"

using namespace mpm_lig;

namespace {

Mat3 shear_increment(int k) {
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 2e-3 * (1.0 + 0.1 * (k % 3));
  dF(1, 1) = 1.0 - 5e-4;
  return dF;
}

bool same_stress(rve::Rve& a, rve::Rve& b) {
  const Mat3 sa = a.stress(), sb = b.stress();
  for (int i = 0; i < 9; ++i) {
    if (sa.data()[i] != sb.data()[i])
      return false;
  }
  return true;
}

//! Contacts (pairs and forces) and placements bit for bit.
void expect_same_grains(rve::Rve& moved, rve::Rve& twin, const std::string& when) {
  const auto a = moved.engine().contacts(), b = twin.engine().contacts();
  ASSERT_EQ(a.size(), b.size()) << when << ": contact count";
  ASSERT_GT(a.size(), 0u);
  for (std::size_t c = 0; c < a.size(); ++c) {
    EXPECT_EQ(a[c].id_i, b[c].id_i) << when << ", contact " << c;
    EXPECT_EQ(a[c].id_j, b[c].id_j) << when << ", contact " << c;
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(a[c].force[k], b[c].force[k]) << when << ", force of contact " << c;
  }
  const rve::Placement pa = rve::take_placement(moved.engine());
  const rve::Placement pb = rve::take_placement(twin.engine());
  EXPECT_EQ(pa.x, pb.x) << when << ": grain positions";
  EXPECT_EQ(pa.image, pb.image) << when << ": image flags";
  EXPECT_TRUE(same_stress(moved, twin)) << when << ": stress";
}

}  // namespace

TEST(RveMigration, MovedRveKeepsContactHistoryAndPlacement) {
  nlohmann::json json = test::small_rve_json();
  json["substeps"] = {{"fixed", 30}};
  const rve::RveSpec spec = test::parse_rve(json);
  const std::string dir = std::string(MPM_LIG_BINARY_DIR) + "/test_rve_migration_files";
  const std::string packing = test::consolidated_packing(spec, dir);
  const std::string file = dir + "/point_0.restart";
  auto twin = rve::Rve::from_restart(spec, packing, MPI_COMM_WORLD, "twin");
  auto leaving = rve::Rve::from_restart(spec, packing, MPI_COMM_WORLD, "leaving");
  auto unplaced = rve::Rve::from_restart(spec, packing, MPI_COMM_WORLD, "control: no placement");
  for (int k = 0; k < 8; ++k) {
    twin->deform(shear_increment(k));
    leaving->deform(shear_increment(k));
    unplaced->deform(shear_increment(k));
  }
  // The move, as DemRveMaterial::migrate makes it (here both halves on one rank).
  const rve::Rve::State state = coupling::send_rve(*leaving, file);
  double packed[coupling::rve_state_width()];
  coupling::pack_state(state, packed);
  leaving.reset();
  auto moved =
      coupling::receive_rve(spec, file, coupling::unpack_state(packed), MPI_COMM_WORLD, "moved");
  EXPECT_FALSE(std::filesystem::exists(file)) << "the moved RVE's restart file was left behind";
  EXPECT_FALSE(std::filesystem::exists(rve::Rve::placement_file(file)));
  // Control 1: the same moment saved, read back without the exact placement (and with the
  // set-up `run 0` of a clone).
  unplaced->write_checkpoint(dir + "/unplaced.restart");
  const rve::Rve::State unplaced_state = unplaced->state();
  unplaced = rve::Rve::from_restart(spec, dir + "/unplaced.restart", MPI_COMM_WORLD, "unplaced");
  unplaced->restore(unplaced_state);
  bool unplaced_left = false;
  for (int k = 8; k < 40; ++k) {
    twin->deform(shear_increment(k));
    moved->deform(shear_increment(k));
    unplaced->deform(shear_increment(k));
    if (k == 8)
      expect_same_grains(*moved, *twin, "first update after the move");
    unplaced_left = unplaced_left || !same_stress(*unplaced, *twin);
  }
  ASSERT_GT(-twin->stress().trace(), 0.0) << "the sheared packing carries no stress";
  expect_same_grains(*moved, *twin, "32 updates after the move");
  EXPECT_EQ(moved->state().particle_steps, twin->state().particle_steps);
  EXPECT_TRUE(unplaced_left) << "control: a move without the placement left no trace; the "
                                "comparison cannot see a lost placement";
}
