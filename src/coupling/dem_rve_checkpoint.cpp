// DemRveMaterial's checkpoint hooks: what a checkpoint keeps of every DEM point, gathered from
// the parts that hold it (docs/DESIGN.md §9).
#include <algorithm>
#include <stdexcept>

#include "coupling/dem_rve_material.h"
#include "coupling/point_bundle.h"
#include "coupling/point_checkpoint.h"

namespace mpm_lig::coupling {
namespace {

// Every point's members in its writer's bundle (kPointIndexWidth values per point); absent
// in checkpoints of format 4 and before, whose points are files of their own.
constexpr const char* kBundleIndexName = "bundle_index";
constexpr const char* kBundleMembersName = "bundle_members_per_point";

}  // namespace

void DemRveMaterial::write_checkpoint(materials::CheckpointWriter& out, std::size_t points) {
  if (!rves_ || !rves_->dealt())
    throw std::logic_error(path_ + ": checkpoint before the first update");
  if (points != points_)
    throw std::logic_error(path_ + ": checkpoint of " + std::to_string(points) + " points, not " +
                           std::to_string(points_));
  const std::vector<double> index = rves_->write_bundle(out);
  const RveLayout& layout = rves_->layout();
  const QuietPoints& quiet = selection_.quiet();
  const SteadyFlow& flow = selection_.flow();
  std::vector<double> owned;
  for (const std::size_t p : layout.owned()) {
    PointCheckpoint saved{results_.stress[p], results_.substeps[p], rves_->state(p)};
    std::copy(work_.row(p), work_.row(p) + DemWork::kValues, saved.work);
    quiet.save_row(p, saved.quiet);
    flow.save_row(p, saved.flow);
    pack(saved, owned);
  }
  write_points(out, layout.gather(owned, static_cast<int>(point_checkpoint_width())));
  out.write(kBundleIndexName, layout.gather(index, static_cast<int>(kPointIndexWidth)));
  out.set(kBundleMembersName, static_cast<double>(kPointMembers));
  out.set("updates", static_cast<double>(updates_));
  out.set("particle_steps", cost_.particle_steps);
  for (const QuietStatField& f : kQuietStatFields)
    out.set(f.name, quiet.stats().*f.value);
  for (const SteadyFlowStatField& f : kSteadyFlowStatFields)
    out.set(f.name, flow.stats().*f.value);
  schedule_.write_checkpoint(out, layout);
  schedule_.flush_record();
}

void DemRveMaterial::restore_checkpoint(const materials::CheckpointReader& in,
                                        const std::vector<Mat3>& stress) {
  if (stress.size() != points_)
    throw std::logic_error(path_ + ": restore of " + std::to_string(stress.size()) +
                           " points, not " + std::to_string(points_));
  if (!rves_)
    throw std::logic_error(path_ + ": restore before prepare()");
  const std::vector<double> rows = read_points(in, points_);
  const std::vector<double> index =
      in.has(kBundleIndexName) ? in.read(kBundleIndexName) : std::vector<double>();
  if (!index.empty() && index.size() != points_ * kPointIndexWidth)
    throw std::runtime_error(in.describe() + ": the bundle index holds " +
                             std::to_string(index.size() / kPointIndexWidth) +
                             " DEM points, the case has " + std::to_string(points_));
  const double start = MPI_Wtime();
  rves_->deal(points_);
  schedule_.restore_checkpoint(in, rves_->layout());
  results_.start(points_);
  start_ledgers();
  QuietPoints& quiet = selection_.quiet();
  SteadyFlow& flow = selection_.flow();
  for (std::size_t p = 0; p < points_; ++p) {
    const PointCheckpoint saved = unpack(rows.data() + p * point_checkpoint_width());
    results_.stress[p] = saved.stress;
    results_.substeps[p] = saved.substeps;
    results_.dem_pressure[p] = saved.rve.last_mean_stress;
    results_.net_shear[p] = rve::shear_of_strain(saved.rve.strain, spec_.dimension);
    work_.restore_row(p, saved.work);
    quiet.restore_row(p, saved.quiet);
    flow.restore_row(p, saved.flow);
    if (rves_->layout().owns(p))
      rves_->restore(p, in, index.empty() ? nullptr : index.data() + p * kPointIndexWidth,
                     saved.rve);
  }
  if (!index.empty())
    rves_->finish_restore();
  updates_ = static_cast<long>(in.get("updates"));
  QuietStats stats;
  for (const QuietStatField& f : kQuietStatFields)
    stats.*f.value = in.get(f.name);
  quiet.restore_stats(stats);
  SteadyFlowStats flow_stats;
  for (const SteadyFlowStatField& f : kSteadyFlowStatFields)
    flow_stats.*f.value = in.get(f.name);
  flow.restore_stats(flow_stats);
  cost_.simulations = points_;
  cost_.particle_steps = in.get("particle_steps");
  schedule_.start_record(rank_, work_dir_, points_, true, updates_);
  cost_.preparation_seconds += MPI_Wtime() - start;
}

}  // namespace mpm_lig::coupling
