// Engines print nothing on the process's stdout/stderr (their screen is an in-memory record),
// including LIGGGHTS's "version 3 8" at read_restart and its "Style collision" warnings for
// every instance after the first; what was silenced stays in recent_output().
#include <gtest/gtest.h>

#include <cstdio>

#include "dem/engine.h"
#include "dem_scripts.h"

namespace mpm_lig::dem::test {
namespace {

class Silence : public ::testing::TestWithParam<std::string> {};

TEST_P(Silence, NothingReachesStdoutOrStderr) {
  const std::string restart =
      std::string(MPM_LIG_BINARY_DIR) + "/silence_" + GetParam() + ".restart";
  Box box;
  box.hi = Vec3::Constant(0.02);
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  std::string second_output;
  {
    auto first = create_engine(GetParam(), MPI_COMM_SELF, {"first", ""});
    auto second = create_engine(GetParam(), MPI_COMM_SELF, {"second", ""});
    second->commands(setup_script(GetParam(), box, true, Material{}));
    second->commands(grains_script(jittered_packing(2, 0.01, 5u), Material{}));
    second->commands(dynamics_script(1e-6, "p"));
    second->command("run 10");
    second->command("write_restart " + restart);
    second->command("clear");
    second->command("read_restart " + restart);
    second_output = second->recent_output();
  }
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  std::remove(restart.c_str());
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  EXPECT_NE(second_output.find("Step"), std::string::npos) << second_output;  // thermo kept
  if (GetParam() == "liggghts") {
    EXPECT_NE(second_output.find("version 3 8"), std::string::npos) << second_output;
    EXPECT_NE(second_output.find("'Style collision' warnings"), std::string::npos) << second_output;
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, Silence, ::testing::Values("liggghts", "lammps"));

}  // namespace
}  // namespace mpm_lig::dem::test
