#include "coupling/owned_rves.h"

#include <array>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "core/mpi_session.h"
#include "coupling/point_bundle.h"
#include "coupling/point_results.h"
#include "coupling/rve_migration.h"
#include "rve/observables.h"
#include "rve/snapshot.h"

namespace mpm_lig::coupling {
namespace {

//! A point's own checkpoint file: a moving RVE's, and every point's in format 4 and before.
std::string checkpoint_file(const std::string& dir, std::size_t point) {
  return dir + "/point_" + std::to_string(point) + ".restart";
}

}  // namespace

OwnedRves::OwnedRves(const rve::RveSpec& spec, int ranks_per_rve, PointLabel label,
                     const materials::MaterialContext& context)
    : spec_(spec),
      ranks_per_rve_(ranks_per_rve),
      label_(std::move(label)),
      comm_(context.comm),
      work_dir_(context.work_dir),
      hooks_(context.hooks) {}

OwnedRves::~OwnedRves() {
  // The folder moving RVEs pass through is empty between moves.
  if (label_.rank == 0 && !work_dir_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(work_dir_ + "/migration", ignored);
  }
}

void OwnedRves::deal(std::size_t points) {
  layout_ = std::make_unique<RveLayout>(comm_, ranks_per_rve_, points);
  rves_.clear();
  rves_.resize(points);
}

void OwnedRves::clone(const std::vector<Packing>& packings, const PackingOrder& order) {
  for (const std::size_t p : layout_->owned()) {
    rves_[p] = or_end_job(label_(p) + " not cloned", [&] {
      return rve::Rve::from_restart(spec_, packings[order.of(p)].restart_file,
                                    layout_->group_comm(), label_(p));
    });
  }
}

void OwnedRves::inject_fault_if_asked(std::size_t point, rve::Rve& rve, long update) const {
  if (hooks_.fault_point < 0 || static_cast<std::size_t>(hooks_.fault_point) != point)
    return;
  if (update == hooks_.fault_update)
    rve.engine().command("mpm_lig_injected_fault (MPM_LIG_FAULT_POINT)");
}

std::vector<double> OwnedRves::deform(const DemBatch& batch, const std::vector<Mat3>& stress,
                                      long update, rve::Rve::EngineRun run, bool set_up) {
  std::vector<double> rows;
  for (const std::size_t p : layout_->owned()) {
    rve::Rve& rve = *rves_[p];
    if (set_up)
      rve.require_setup();
    Mat3 sigma = stress[p];
    double steps = 0.0;
    const double start = MPI_Wtime();
    if (batch.runs(p)) {
      inject_fault_if_asked(p, rve, update);
      // One rank's failure must end the whole job: the others are about to wait for it.
      try {
        steps = rve.deform(batch.increment(p), 0, run);
        // The contact forces are not needed here: what the blow-up check reads comes from
        // the overlaps (docs/hpc.md, the per-update fixed cost).
        const rve::Observables now = rve.observe_health();
        sigma = now.stress;
        // Blow-up only: the energy ratios need a strain rate, which a point at rest has not.
        rve.check_blow_up(now);
      } catch (const std::exception& e) {
        abort_job(label_(p) + " failed at MPM update " + std::to_string(update) + ": " + e.what() +
                      "\nlast engine output:\n" + rve.engine().recent_output(),
                  kExitEngineFailure);
      }
    }
    append_result(rows, sigma, steps, rve.net_shear(), MPI_Wtime() - start);
  }
  return rows;
}

void OwnedRves::migrate(const std::vector<int>& owners) {
  const std::vector<int> before = layout_->owners();
  const int group = layout_->group();
  const std::string folder = work_dir_ + "/migration";
  if (label_.rank == 0)
    std::filesystem::create_directories(folder);
  MPI_Barrier(comm_);
  // An RVE moves through its checkpoint files (engine restart and exact placement) and its
  // Rve::State: the new owner continues it bit-identically (docs/DESIGN.md §10). All leaving
  // RVEs are written first, so the groups write in parallel, then read in parallel.
  const auto file = [&](std::size_t p) { return checkpoint_file(folder, p); };
  std::vector<std::size_t> moving;
  for (std::size_t p = 0; p < rves_.size(); ++p) {
    if (owners[p] != before[p])
      moving.push_back(p);
  }
  constexpr std::size_t kState = rve_state_width();
  std::vector<std::array<double, kState>> states(moving.size());
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const std::size_t p = moving[k];
    if (before[p] != group)
      continue;
    const rve::Rve::State st =
        or_end_job(label_(p) + ": not moved to rank group " + std::to_string(owners[p]),
                   [&] { return send_rve(*rves_[p], file(p)); });
    pack_state(st, states[k].data());
    rves_[p].reset();
  }
  // The owner's leader sends the state once its files are written (and checked).
  for (std::size_t k = 0; k < moving.size(); ++k)
    MPI_Bcast(states[k].data(), static_cast<int>(kState), MPI_DOUBLE,
              before[moving[k]] * ranks_per_rve_, comm_);
  layout_->reassign(owners);
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const std::size_t p = moving[k];
    if (owners[p] != group)
      continue;
    rves_[p] =
        or_end_job(label_(p) + " not moved from rank group " + std::to_string(before[p]), [&] {
          return receive_rve(spec_, file(p), unpack_state(states[k].data()), layout_->group_comm(),
                             label_(p));
        });
  }
}

std::vector<double> OwnedRves::write_bundle(materials::CheckpointWriter& out) {
  const std::string not_written = ": checkpoint not written (the previous one is kept)";
  std::vector<double> index;
  // The group's leader writes its RVEs into one bundle, in point order (docs/hpc.md §3).
  std::unique_ptr<PointBundleWriter> bundle;
  if (!layout_->owned().empty())
    bundle = or_end_job(label_.path + not_written, [&] {
      return std::make_unique<PointBundleWriter>(out.folder(), scratch_folder(),
                                                 group_leader_rank(), layout_->group_comm());
    });
  for (const std::size_t p : layout_->owned())
    or_end_job(label_(p) + not_written, [&] { bundle->add(*rves_[p], index); });
  const std::string digest =
      bundle ? or_end_job(label_.path + not_written, [&] { return bundle->close(); }) : "";
  // Every rank learns every bundle's digest (64 hexadecimal characters, or none).
  constexpr int kHexLength = 64;
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  std::string mine = digest;
  mine.resize(kHexLength, ' ');
  std::string all(static_cast<std::size_t>(ranks * kHexLength), ' ');
  MPI_Allgather(mine.data(), kHexLength, MPI_CHAR, all.data(), kHexLength, MPI_CHAR, comm_);
  for (int r = 0; r < ranks; ++r) {
    if (all[static_cast<std::size_t>(r * kHexLength)] != ' ')
      out.record_digest(io::bundle_name(r),
                        all.substr(static_cast<std::size_t>(r * kHexLength), kHexLength));
  }
  return index;
}

void OwnedRves::restore(std::size_t point, const materials::CheckpointReader& in,
                        const double* index, const rve::Rve::State& state) {
  rves_[point] = or_end_job(in.describe() + ": " + label_(point) + " not restored", [&] {
    // Format 5: the point's byte ranges of its writer's bundle; before, files of its own.
    const std::string file = index == nullptr ? checkpoint_file(in.folder(), point)
                                              : unbundle_point(in.folder(), index, scratch_folder(),
                                                               layout_->group_comm());
    return rve::Rve::from_checkpoint(spec_, file, layout_->group_comm(), label_(point));
  });
  rves_[point]->restore(state);
}

void OwnedRves::finish_restore() {
  remove_scratch(scratch_folder(), layout_->group_comm());
}

int OwnedRves::group_leader_rank() const {
  return label_.rank - label_.rank % ranks_per_rve_;
}

std::string OwnedRves::scratch_folder() const {
  if (work_dir_.empty())
    throw std::logic_error(label_.path + ": no work folder for the checkpoint's scratch files");
  return work_dir_ + "/checkpoint_scratch_rank_" + std::to_string(group_leader_rank());
}

void OwnedRves::write_snapshot(std::size_t point, const std::string& prefix) {
  if (layout_->owns(point))
    rve::write_snapshot(*rves_[point], prefix, layout_->group_leader());
}

}  // namespace mpm_lig::coupling
