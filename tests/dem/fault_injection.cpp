// Fault injection for the engine-failure guard (core/mpi_session.cpp, dem/guarded_engine.cpp).
// usage: mpirun -np 2 dem_fault_injection ENGINE FAULT
//   Every rank runs its own instance ("RVE <16 + rank>") on a split communicator; rank 1's
//   instance then fails with FAULT while rank 0 waits in a collective call on MPI_COMM_WORLD
//   (which would hang forever if the failure only ended rank 1).
//   FAULT: unknown_command | virial_not_tallied
#include <mpi.h>

#include <cstdio>
#include <string>

#include "core/mpi_session.h"
#include "dem/engine.h"
#include "dem_scripts.h"

using namespace mpm_lig;
using namespace mpm_lig::dem;

int main(int argc, char** argv) {
  MpiSession mpi(&argc, &argv);
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s ENGINE unknown_command|virial_not_tallied\n", argv[0]);
    return 2;
  }
  const std::string engine_name = argv[1], fault = argv[2];
  MPI_Comm own;
  MPI_Comm_split(MPI_COMM_WORLD, mpi.rank(), 0, &own);

  const test::Material material;
  Box box;
  box.hi = Vec3::Constant(0.04);
  auto engine = create_engine(engine_name, own, {"RVE " + std::to_string(16 + mpi.rank()), ""});
  engine->commands(test::setup_script(engine_name, box, true, material));
  engine->commands(test::grains_script(test::jittered_packing(4, 0.01, 3u), material));
  engine->commands(test::dynamics_script(1e-6, "p"));
  engine->command("run 10");

  if (mpi.rank() == 1) {
    if (fault == "unknown_command") {
      engine->command("this_is_not_a_command 1 2 3");
    } else {
      // Read a pressure whose virial nothing asked the engine to tally on this step.
      engine->command("thermo_style custom step atoms");
      engine->command("run 10");
      engine->compute_vector("p", 6);
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  std::fprintf(stderr, "fault injection: no failure happened\n");
  MPI_Comm_free(&own);
  return 0;
}
