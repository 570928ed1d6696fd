// Both engine modules live in one process (each in its own dlopen'ed module): a LIGGGHTS and a
// LAMMPS instance alive at the same time, their runs interleaved, reproduce their solo runs
// bit for bit.
#include <gtest/gtest.h>

#include <array>

#include "dem/engine.h"
#include "dem_scripts.h"

namespace mpm_lig::dem::test {
namespace {

std::unique_ptr<Engine> sheared_packing(const std::string& engine_name) {
  Box box;
  box.hi = Vec3::Constant(0.04);
  box.xy = 0.001;
  auto engine = create_engine(engine_name, MPI_COMM_SELF, {engine_name, ""});
  engine->commands(setup_script(engine_name, box, true, Material{}));
  engine->commands(grains_script(jittered_packing(4, 0.01, 9u), Material{}));
  engine->commands(dynamics_script(1e-6, "p"));
  engine->command("fix shear all deform 1 xy erate 20.0 remap x");
  return engine;
}

TEST(TwoEngines, InterleavedRunsMatchSoloRuns) {
  const std::array<std::string, 2> names = {"liggghts", "lammps"};
  std::array<std::vector<double>, 2> solo;
  for (int k = 0; k < 2; ++k) {
    auto engine = sheared_packing(names[k]);
    engine->command("run 100");
    engine->command("run 100");
    solo[k] = engine->compute_vector("p", 6);
  }
  std::array<std::unique_ptr<Engine>, 2> both = {sheared_packing(names[0]),
                                                 sheared_packing(names[1])};
  for (int step = 0; step < 2; ++step)
    for (auto& engine : both)
      engine->command("run 100");
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(both[k]->name(), names[k]);
    EXPECT_EQ(both[k]->compute_vector("p", 6), solo[k]) << names[k];
  }
}

TEST(TwoEngines, UnknownEngineNameListsTheKnownOnes) {
  try {
    create_engine("yade", MPI_COMM_SELF, {"x", ""});
    FAIL() << "no error for an unknown engine";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("known: liggghts, lammps"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mpm_lig::dem::test
