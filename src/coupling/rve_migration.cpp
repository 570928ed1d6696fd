#include "coupling/rve_migration.h"

#include <algorithm>
#include <filesystem>

namespace mpm_lig::coupling {

void pack_state(const rve::Rve::State& s, double* v) {
  std::copy_n(s.rotation.data(), 9, v);
  std::copy_n(s.streaming.data(), 9, v + 9);
  v[18] = s.particle_steps;
  v[19] = s.last_mean_stress;
}

rve::Rve::State unpack_state(const double* v) {
  rve::Rve::State s;
  s.rotation = Eigen::Map<const Mat3>(v);
  s.streaming = Eigen::Map<const Mat3>(v + 9);
  s.particle_steps = v[18];
  s.last_mean_stress = v[19];
  return s;
}

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
