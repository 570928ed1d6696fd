#include "coupling/rve_migration.h"

#include <filesystem>

namespace mpm_lig::coupling {

rve::Rve::State send_rve(rve::Rve& rve, const std::string& file) {
  rve.write_checkpoint(file);
  return rve.state();
}

std::unique_ptr<rve::Rve> receive_rve(const rve::RveSpec& spec, const std::string& file,
                                      const rve::Rve::State& state, MPI_Comm comm,
                                      const std::string& label) {
  std::unique_ptr<rve::Rve> rve = rve::Rve::from_checkpoint(spec, file, comm, label);
  rve->restore(state);
  // Every rank of the group has read the files before they go.
  MPI_Barrier(comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) {
    std::filesystem::remove(file);
    std::filesystem::remove(rve::Rve::placement_file(file));
  }
  return rve;
}

}  // namespace mpm_lig::coupling
