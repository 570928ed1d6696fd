#include "coupling/packings.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "core/stop_signal.h"
#include "coupling/job_failure.h"
#include "coupling/rve_layout.h"
#include "io/atomic_file.h"
#include "rve/consolidation.h"
#include "rve/observables.h"
#include "rve/rve.h"

namespace mpm_lig::coupling {

std::size_t PackingOrder::of(std::size_t point) const {
  if (!scattered)
    return point % count;
  // splitmix64's finaliser: neighbouring indices land on unrelated packings.
  std::uint64_t z = static_cast<std::uint64_t>(point) + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<std::size_t>(z % count);
}
namespace {

//! Strain of the uniaxial probe that measures a packing's constrained modulus: small enough
//! to stay elastic, large enough to rise above the packing's stress fluctuations.
constexpr double kProbeStrain = 1e-4;
constexpr int kPackingValues = 12;  // stress (9), void ratio, wave and lateral moduli

//! Constrained modulus M = Δσ_xx / ε_xx and lateral modulus Δσ_yy / ε_xx of `packing` from a
//! uniaxial compression of `rve`. Destroys the state of `rve`: call after its restart file is
//! written.
void probe_moduli(rve::Rve& rve, Packing& packing) {
  const Mat3 before = rve.stress();
  Mat3 dF = Mat3::Identity();
  dF(0, 0) -= kProbeStrain;
  rve.deform(dF);
  const Mat3 change = rve.stress() - before;
  packing.wave_modulus = std::abs(change(0, 0)) / kProbeStrain;
  packing.lateral_modulus = -change(1, 1) / kProbeStrain;
}

//! The kPackingValues numbers of `p` the rank groups exchange (packing_from reads them back).
std::vector<double> packing_values(const Packing& p) {
  std::vector<double> v(p.stress.data(), p.stress.data() + 9);
  v.push_back(p.void_ratio);
  v.push_back(p.wave_modulus);
  v.push_back(p.lateral_modulus);
  return v;
}

Packing packing_from(const double* v, const std::string& restart_file) {
  Packing p;
  p.stress = Eigen::Map<const Mat3>(v);
  p.void_ratio = v[9];
  p.wave_modulus = v[10];
  p.lateral_modulus = v[11];
  p.restart_file = restart_file;
  return p;
}

//! Packing k, generated and consolidated (saved to `file`) or loaded from the case's restart
//! file, on the ranks of `group_comm`. Throws StopRequested when they agree to stop.
Packing prepare_packing(const rve::RveSpec& spec, std::size_t k, const std::string& file,
                        MPI_Comm group_comm, const std::string& path, const TestHooks& hooks) {
  const std::string label = path + " packing " + std::to_string(k);
  hooks.at(TestHooks::Moment::packing_started, static_cast<long>(k), 0);
  std::unique_ptr<rve::Rve> rve;
  if (spec.restart_file.empty()) {
    rve::RveSpec seeded = spec;
    seeded.seed += k;
    rve = rve::Rve::generate(seeded, group_comm, label);
    // A missed target void ratio ends the whole job: other rank groups wait for this one.
    or_end_job(label + " not prepared",
               [&] { rve::require_void_ratio(*rve, rve::consolidate(*rve)); });
    // Saved under a temporary name first: a packing file is complete or absent, whatever
    // stops the run while it is written.
    // The engine writes it collectively, so the rename is io::replace_atomically's second
    // half, done once by the group's rank 0.
    const std::string partial = io::temporary_beside(file, ".partial");
    or_end_job(label + " not saved", [&] {
      rve->write_restart(partial);
      int group_rank = 0;
      MPI_Comm_rank(group_comm, &group_rank);
      if (group_rank == 0)
        io::rename_over(partial, file);
      MPI_Barrier(group_comm);
    });
    rve->orient_cell();  // as its clones will be
    rve->use_loading_time_step();
  } else {
    rve = or_end_job(label + " not loaded",
                     [&] { return rve::Rve::from_restart(spec, file, group_comm, label); });
  }
  Packing p;
  const rve::Observables now = rve->observe();
  p.stress = now.stress;
  p.void_ratio = now.void_ratio;
  probe_moduli(*rve, p);
  return p;
}

}  // namespace

std::vector<Packing> prepare_packings(const rve::RveSpec& spec, int count, int ranks_per_rve,
                                      const std::string& path,
                                      const materials::MaterialContext& context) {
  MPI_Comm comm = context.comm;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string& work_dir = context.work_dir;
  if (spec.restart_file.empty()) {
    if (rank == 0)
      std::filesystem::create_directories(work_dir);
    MPI_Barrier(comm);
  }
  std::vector<std::string> files(count);
  for (int k = 0; k < count; ++k) {
    files[k] =
        spec.restart_file.empty()
            ? (std::filesystem::path(work_dir) / ("packing_" + std::to_string(k) + ".restart"))
                  .string()
            : spec.restart_file;
  }
  // The packings are spread over the rank groups like RVEs are.
  RveLayout layout(comm, ranks_per_rve, static_cast<std::size_t>(count));
  std::vector<double> owned;
  int saved = 0;
  bool stopped = false;
  for (const std::size_t k : layout.owned()) {
    try {
      const std::vector<double> v = packing_values(
          prepare_packing(spec, k, files[k], layout.group_comm(), path, context.hooks));
      owned.insert(owned.end(), v.begin(), v.end());
      ++saved;
    } catch (const StopRequested&) {
      stopped = true;  // this group's ranks agreed; the others learn it below
      break;
    }
  }
  // Every rank gets here, stopped or not: the stop is decided for the whole job at once.
  int counts[2] = {stopped ? 1 : 0, layout.group_leader() ? saved : 0};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT, MPI_SUM, comm);
  if (counts[0] > 0 || stop_requested(comm)) {
    std::string where = spec.restart_file.empty()
                            ? std::to_string(counts[1]) + " of " + std::to_string(count) +
                                  " packings saved in " + work_dir +
                                  " (a later run prepares them all again)"
                            : "its packing loaded from " + spec.restart_file;
    throw StopRequested("stopped by a signal while preparing " + path + ": " + where +
                        "; no results and no checkpoint were written");
  }
  const std::vector<double> all = layout.gather(owned, kPackingValues);
  std::vector<Packing> packings;
  for (int k = 0; k < count; ++k)
    packings.push_back(packing_from(&all[k * kPackingValues], files[k]));
  return packings;
}

}  // namespace mpm_lig::coupling
