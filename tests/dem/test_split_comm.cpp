// Two instances, one per rank on split communicators, give exactly the stresses of the same
// two instances run one after the other on one rank. Runs under mpirun -np 2.
#include <gtest/gtest.h>

#include "dem/engine.h"
#include "dem_scripts.h"

namespace mpm_lig::dem::test {
namespace {

//! Build packing `seed`, shear it, return the virial pressure tensor.
std::vector<double> sheared_pressure(const std::string& engine_name, MPI_Comm comm, unsigned seed) {
  const Material material;
  Box box;
  box.hi = Vec3::Constant(0.04);
  box.xy = 0.001;  // triclinic, so that fix deform may shear it
  auto engine = create_engine(engine_name, comm, {"RVE " + std::to_string(seed), ""});
  engine->commands(setup_script(engine_name, box, true, material));
  engine->commands(grains_script(jittered_packing(4, 0.01, seed), material));
  engine->commands(dynamics_script(1e-6, "p"));
  engine->command("fix shear all deform 1 xy erate 20.0 remap x");
  engine->command("run 300");
  return engine->compute_vector("p", 6);
}

class SplitCommunicators : public ::testing::TestWithParam<std::string> {};

TEST_P(SplitCommunicators, MatchSerialRunsExactly) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2) << "run under mpirun -np 2";
  MPI_Comm own;
  MPI_Comm_split(MPI_COMM_WORLD, rank, 0, &own);
  const unsigned seeds[2] = {101u, 202u};
  std::vector<double> mine = sheared_pressure(GetParam(), own, seeds[rank]);
  std::vector<double> split(12);
  MPI_Allgather(mine.data(), 6, MPI_DOUBLE, split.data(), 6, MPI_DOUBLE, MPI_COMM_WORLD);
  MPI_Comm_free(&own);

  if (rank == 0) {
    for (int k = 0; k < 2; ++k) {
      const std::vector<double> serial = sheared_pressure(GetParam(), MPI_COMM_SELF, seeds[k]);
      for (int c = 0; c < 6; ++c)
        EXPECT_EQ(serial[c], split[6 * k + c]) << "instance " << k << " component " << c;
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

INSTANTIATE_TEST_SUITE_P(Engines, SplitCommunicators, ::testing::Values("liggghts", "lammps"));

}  // namespace
}  // namespace mpm_lig::dem::test
