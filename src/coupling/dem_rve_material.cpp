#include "coupling/dem_rve_material.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "core/mpi_session.h"
#include "core/stop_signal.h"
#include "coupling/point_bundle.h"
#include "coupling/point_checkpoint.h"
#include "coupling/rve_migration.h"
#include "dem/file_name.h"
#include "io/atomic_file.h"
#include "rve/consolidation.h"
#include "rve/observables.h"
#include "rve/snapshot.h"

namespace mpm_lig::coupling {
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

constexpr const char* kOwnersName = "rve_owner";   // groups, then every point's group
constexpr const char* kSteppingName = "stepping";  // StepTotals ×3, migrations, rebalances
// Every point's members in its writer's bundle (kPointIndexWidth values per point); absent
// in checkpoints of format 4 and before, whose points are files of their own.
constexpr const char* kBundleIndexName = "bundle_index";
constexpr const char* kBundleMembersName = "bundle_members_per_point";

std::string checkpoint_file(const std::string& dir, std::size_t point) {
  return dir + "/point_" + std::to_string(point) + ".restart";
}

//! Run `work` on one RVE's files; a failure ends the whole job at once with `what` and the
//! reason: the other ranks are about to wait for this one in a collective call.
template <class Work>
auto or_end_job(const std::string& what, Work&& work) {
  try {
    return work();
  } catch (const StopRequested&) {
    throw;  // agreed on by the RVE's ranks: the caller stops with the others
  } catch (const std::exception& e) {
    abort_job(what + ": " + e.what(), 1);
  }
}

}  // namespace

DemRveMaterial::DemRveMaterial(const CaseNode& node) : path_(node.path()) {
  node.get<std::string>("type");
  spec_ = rve::parse_rve_spec(node.child("rve"));
  packing_count_ = node.get_or<int>("packings", 1);
  if (packing_count_ < 1)
    node.fail("packings", "must be >= 1");
  if (!spec_.restart_file.empty() && packing_count_ != 1)
    node.fail("packings", "must be 1 when rve.restart_file gives the packing");
  ranks_per_rve_ = node.get_or<int>("ranks_per_rve", 1);
  if (ranks_per_rve_ < 1)
    node.fail("ranks_per_rve", "must be >= 1");
  if (node.has("quiet"))
    quiet_spec_ = parse_quiet(node.child("quiet"));
  if (node.has("start_as_continuum"))
    continuum_start_spec_ = parse_continuum_start(node.child("start_as_continuum"));
  if (node.has("balance"))
    balance_spec_ = parse_balance(node.child("balance"));
}

DemRveMaterial::~DemRveMaterial() {
  // The folder moving RVEs pass through is empty between moves.
  if (rank_ == 0 && !work_dir_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(work_dir_ + "/migration", ignored);
  }
}

std::string DemRveMaterial::point_label(std::size_t point) const {
  return path_ + " material point " + std::to_string(point) + " (MPI rank " +
         std::to_string(rank_) + ")";
}

void DemRveMaterial::check_dimension(const CaseNode& node, int dimension) const {
  if (dimension == 3 && spec_.dimension == 2)
    node.child("rve").fail("dimension", "2D disc packings cannot serve a 3D MPM analysis");
}

void DemRveMaterial::check_run(std::size_t points, int ranks, const std::string& run_dir,
                               MemoryBudget& budget) const {
  if (ranks % ranks_per_rve_ != 0)
    throw CaseError(path_ + ".ranks_per_rve", std::to_string(ranks_per_rve_) +
                                                  " does not divide the " + std::to_string(ranks) +
                                                  " MPI ranks of this run");
  if (points > 0 && static_cast<std::size_t>(packing_count_) > points)
    throw CaseError(path_ + ".packings", std::to_string(packing_count_) + " packings for " +
                                             std::to_string(points) +
                                             " material points: some would never be used");
  const std::string unusable = dem::unusable_file_name(run_dir);
  if (!unusable.empty())
    throw CaseError(path_, "the DEM engine writes its packings into the output folder '" + run_dir +
                               "': " + unusable);
  // Each rank of a group holds its share of every RVE the group owns, and while preparing,
  // one packing at a time.
  const double groups = ranks / ranks_per_rve_;
  const double rves = std::ceil(static_cast<double>(points) / groups);
  budget.add(path_ + ".rve.grains",
             (rves + 1.0) * rve::instance_memory_bytes(spec_) / ranks_per_rve_,
             std::to_string(static_cast<long>(rves)) + " RVEs of " + std::to_string(spec_.grains) +
                 " grains per rank group",
             true);
}

void DemRveMaterial::prepare(const materials::MaterialContext& context) {
  const double start = MPI_Wtime();
  comm_ = context.comm;
  hooks_ = context.hooks;
  MPI_Comm_rank(comm_, &rank_);
  const std::string& work_dir = context.work_dir;
  work_dir_ = work_dir;
  if (spec_.restart_file.empty()) {
    if (rank_ == 0)
      std::filesystem::create_directories(work_dir);
    MPI_Barrier(comm_);
  }
  std::vector<std::string> files(packing_count_);
  for (int k = 0; k < packing_count_; ++k) {
    files[k] =
        spec_.restart_file.empty()
            ? (std::filesystem::path(work_dir) / ("packing_" + std::to_string(k) + ".restart"))
                  .string()
            : spec_.restart_file;
  }
  // The packings are spread over the rank groups like RVEs are.
  RveLayout layout(comm_, ranks_per_rve_, static_cast<std::size_t>(packing_count_));
  std::vector<double> owned;
  int saved = 0;
  bool stopped = false;
  for (const std::size_t k : layout.owned()) {
    try {
      const std::vector<double> v =
          packing_values(prepare_packing(k, files[k], layout.group_comm()));
      owned.insert(owned.end(), v.begin(), v.end());
      ++saved;
    } catch (const StopRequested&) {
      stopped = true;  // this group's ranks agreed; the others learn it below
      break;
    }
  }
  // Every rank gets here, stopped or not: the stop is decided for the whole job at once.
  int counts[2] = {stopped ? 1 : 0, layout.group_leader() ? saved : 0};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT, MPI_SUM, comm_);
  if (counts[0] > 0 || stop_requested(comm_)) {
    std::string where = spec_.restart_file.empty()
                            ? std::to_string(counts[1]) + " of " + std::to_string(packing_count_) +
                                  " packings saved in " + work_dir +
                                  " (a later run prepares them all again)"
                            : "its packing loaded from " + spec_.restart_file;
    throw StopRequested("stopped by a signal while preparing " + path_ + ": " + where +
                        "; no results and no checkpoint were written");
  }
  const std::vector<double> all = layout.gather(owned, kPackingValues);
  packings_.clear();
  for (int k = 0; k < packing_count_; ++k) {
    packings_.push_back(packing_from(&all[k * kPackingValues], files[k]));
  }
  cost_.preparation_seconds += MPI_Wtime() - start;
}

Packing DemRveMaterial::prepare_packing(std::size_t k, const std::string& file,
                                        MPI_Comm group_comm) const {
  const std::string label = path_ + " packing " + std::to_string(k);
  hooks_.at(TestHooks::Moment::packing_started, static_cast<long>(k), 0);
  std::unique_ptr<rve::Rve> rve;
  if (spec_.restart_file.empty()) {
    rve::RveSpec spec = spec_;
    spec.seed += k;
    rve = rve::Rve::generate(spec, group_comm, label);
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
  } else {
    rve = or_end_job(label + " not loaded",
                     [&] { return rve::Rve::from_restart(spec_, file, group_comm, label); });
  }
  Packing p;
  const rve::Observables now = rve->observe();
  p.stress = now.stress;
  p.void_ratio = now.void_ratio;
  probe_moduli(*rve, p);
  return p;
}

double DemRveMaterial::density() const {
  if (packings_.empty())
    throw std::logic_error(path_ + ": density() before prepare()");
  double solid_fraction = 0.0;
  for (const Packing& p : packings_)
    solid_fraction += 1.0 / (1.0 + p.void_ratio);
  return spec_.density * solid_fraction / static_cast<double>(packings_.size());
}

double DemRveMaterial::wave_modulus() const {
  if (packings_.empty())
    throw std::logic_error(path_ + ": wave_modulus() before prepare()");
  double m = 0.0;
  for (const Packing& p : packings_)
    m = std::max(m, p.wave_modulus);
  return m;
}

std::size_t DemRveMaterial::add_points(std::size_t count) {
  if (layout_)
    throw std::logic_error(path_ + ": points added after the first update");
  const std::size_t first = points_;
  points_ += count;
  return first;
}

void DemRveMaterial::set_stress(std::size_t /*point*/, const Mat3& /*sigma*/) {
  throw std::logic_error(path_ +
                         ": a dem_rve point's stress comes from its packing; it cannot be set");
}

Mat3 DemRveMaterial::initial_stress(std::size_t point) const {
  return packings_.at(packing_of(point)).stress;
}

void DemRveMaterial::create_rves() {
  const double start = MPI_Wtime();
  layout_ = std::make_unique<RveLayout>(comm_, ranks_per_rve_, points_);
  stress_.resize(points_);
  substeps_.assign(points_, 0.0);
  dem_pressure_.assign(points_, 0.0);  // a clone has not measured its stress yet
  for (std::size_t p = 0; p < points_; ++p)
    stress_[p] = initial_stress(p);
  rves_.clear();
  rves_.resize(points_);
  for (const std::size_t p : layout_->owned()) {
    rves_[p] = or_end_job(point_label(p) + " not cloned", [&] {
      return rve::Rve::from_restart(spec_, packings_[packing_of(p)].restart_file,
                                    layout_->group_comm(), point_label(p));
    });
  }
  start_work_ledger();
  start_cost_record(false);
  cost_.simulations = points_;
  cost_.preparation_seconds += MPI_Wtime() - start;
}

void DemRveMaterial::start_work_ledger() {
  // A packing read from a restart file has no preparation pressure: its own stress stands in.
  double p = spec_.preparation.confining_pressure;
  if (p <= 0.0 && !packings_.empty())
    p = mean_pressure(packings_.front().stress, spec_.dimension);
  work_.start(points_, static_cast<double>(spec_.grains),
              spec_.substeps.fixed > 0 ? 0 : spec_.substeps.max, p);
  quiet_.start(points_, quiet_spec_, spec_.dimension, spec_.substeps.pressure_floor,
               continuum_start_spec_);
  for (std::size_t point = 0; point < points_; ++point)
    quiet_.set_packing(point, initial_stress(point), packings_[packing_of(point)].wave_modulus,
                       packings_[packing_of(point)].lateral_modulus);
}

void DemRveMaterial::inject_fault_if_asked(std::size_t point, rve::Rve& rve) const {
  if (hooks_.fault_point < 0 || static_cast<std::size_t>(hooks_.fault_point) != point)
    return;
  if (updates_ == hooks_.fault_update)
    rve.engine().command("mpm_lig_injected_fault (MPM_LIG_FAULT_POINT)");
}

std::vector<double> DemRveMaterial::deform_owned(const std::vector<long>& batch_index,
                                                 const std::vector<Mat3>& dF) {
  std::vector<double> owned;
  for (const std::size_t p : layout_->owned()) {
    rve::Rve& rve = *rves_[p];
    double steps = 0.0;
    const double start = MPI_Wtime();
    if (batch_index[p] >= 0) {
      inject_fault_if_asked(p, rve);
      // One rank's failure must end the whole job: the others are about to wait for it.
      try {
        steps = rve.deform(dF[batch_index[p]]);
        // The contact forces are not needed here: what the blow-up check reads comes from
        // the overlaps (docs/hpc.md, the per-update fixed cost).
        const rve::Observables now = rve.observe_health();
        stress_[p] = now.stress;
        // Blow-up only: the energy ratios need a strain rate, which a point at rest has not.
        rve.check_blow_up(now);
      } catch (const std::exception& e) {
        abort_job(point_label(p) + " failed at MPM update " + std::to_string(updates_) + ": " +
                      e.what() + "\nlast engine output:\n" + rve.engine().recent_output(),
                  kExitEngineFailure);
      }
    }
    owned.insert(owned.end(), stress_[p].data(), stress_[p].data() + 9);
    owned.push_back(steps);
    owned.push_back(MPI_Wtime() - start);
  }
  return owned;
}

std::vector<double> DemRveMaterial::predict_steps(const std::vector<long>& batch_index,
                                                  const std::vector<Mat3>& increments) const {
  std::vector<double> steps(points_, 0.0);
  for (std::size_t p = 0; p < points_; ++p) {
    if (batch_index[p] >= 0)
      steps[p] = rve::predicted_substeps(spec_, increments[batch_index[p]], dem_pressure_[p]);
  }
  return steps;
}

std::vector<double> DemRveMaterial::work_of(const std::vector<double>& steps,
                                            const std::vector<long>& batch_index) const {
  std::vector<double> work(points_, 0.0);
  for (std::size_t p = 0; p < points_; ++p) {
    if (batch_index[p] >= 0)
      work[p] = (steps[p] + balance_spec_.update_cost) * static_cast<double>(spec_.grains);
  }
  return work;
}

double DemRveMaterial::fewest_substeps() const {
  return spec_.substeps.fixed > 0 ? spec_.substeps.fixed : spec_.substeps.min;
}

void DemRveMaterial::rebalance(const std::vector<double>& predicted_work) {
  if (!balance_spec_.enabled || layout_->groups() < 2)
    return;
  // Replicated costs and owners only: every rank plans the same moves, and so does a resume.
  // (With rank_speed "measured" the groups' speeds too: the same on every rank, gathered.)
  // What stays of a point's cost is its update at the fewest sub-steps: the peaks above it
  // move on with the deformation (balance.persistence; plan_moves caps it at each cost).
  const std::vector<double> floor(
      points_, (fewest_substeps() + balance_spec_.update_cost) * static_cast<double>(spec_.grains));
  const BalancePlan plan = plan_moves(
      predicted_work, layout_->owners(), layout_->groups(), balance_spec_.threshold,
      balance_spec_.horizon, balance_spec_.move_cost * static_cast<double>(spec_.grains),
      speed_ ? speed_->slowness() : std::vector<double>(), floor, balance_spec_.persistence);
  if (plan.moves == 0)
    return;
  migrate(plan.owner);
  migrations_ += static_cast<double>(plan.moves);
  rebalances_ += 1.0;
}

void DemRveMaterial::migrate(const std::vector<int>& owners) {
  const double start = MPI_Wtime();
  const std::vector<int> before = layout_->owners();
  const int group = layout_->group();
  const std::string folder = work_dir_ + "/migration";
  if (rank_ == 0)
    std::filesystem::create_directories(folder);
  MPI_Barrier(comm_);
  // An RVE moves through its checkpoint files (engine restart and exact placement) and its
  // Rve::State: the new owner continues it bit-identically (docs/DESIGN.md §10). All leaving
  // RVEs are written first, so the groups write in parallel, then read in parallel.
  const auto file = [&](std::size_t p) { return checkpoint_file(folder, p); };
  std::vector<std::size_t> moving;
  for (std::size_t p = 0; p < points_; ++p) {
    if (owners[p] != before[p])
      moving.push_back(p);
  }
  std::vector<std::array<double, kRveStateValues>> states(moving.size());
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const std::size_t p = moving[k];
    if (before[p] != group)
      continue;
    const rve::Rve::State st =
        or_end_job(point_label(p) + ": not moved to rank group " + std::to_string(owners[p]),
                   [&] { return send_rve(*rves_[p], file(p)); });
    pack_state(st, states[k].data());
    rves_[p].reset();
  }
  // The owner's leader sends the state once its files are written (and checked).
  for (std::size_t k = 0; k < moving.size(); ++k)
    MPI_Bcast(states[k].data(), kRveStateValues, MPI_DOUBLE, before[moving[k]] * ranks_per_rve_,
              comm_);
  layout_->reassign(owners);
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const std::size_t p = moving[k];
    if (owners[p] != group)
      continue;
    rves_[p] =
        or_end_job(point_label(p) + " not moved from rank group " + std::to_string(before[p]), [&] {
          return receive_rve(spec_, file(p), unpack_state(states[k].data()), layout_->group_comm(),
                             point_label(p));
        });
  }
  cost_.migration_seconds += MPI_Wtime() - start;
}

void DemRveMaterial::account(const std::vector<double>& predicted_steps,
                             const std::vector<double>& seconds,
                             const std::vector<long>& batch_index) {
  const std::vector<int>& owners = layout_->owners();
  const int groups = layout_->groups();
  predicted_totals_.add(work_of(predicted_steps, batch_index), owners, groups);
  const std::vector<double> work = work_of(substeps_, batch_index);
  work_totals_.add(work, owners, groups);
  seconds_totals_.add(seconds, owners, groups);
  if (balance_spec_.measured_speed) {
    if (!speed_)
      speed_ = std::make_unique<GroupSpeed>(groups);
    speed_->observe(work, seconds, owners);
  }
  if (!record_)
    return;
  record_->add(updates_, groups, predicted_steps, substeps_, seconds, owners);
  if (record_->buffered() >= 100)
    or_end_job(path_ + ": the cost record not written", [&] { record_->flush(); });
}

void DemRveMaterial::start_cost_record(bool resumed) {
  if (rank_ != 0 || work_dir_.empty())
    return;
  record_ = std::make_unique<CostRecord>(work_dir_ + "/cost_record.h5", points_,
                                         static_cast<double>(spec_.grains),
                                         balance_spec_.update_cost, fewest_substeps());
  or_end_job(path_ + ": the cost record not started", [&] {
    std::filesystem::create_directories(work_dir_);
    if (resumed)
      record_->continue_after(updates_);
    else
      record_->create();
  });
}

std::vector<Mat3> DemRveMaterial::dem_increments(const std::vector<std::size_t>& points,
                                                 const std::vector<Mat3>& dF,
                                                 std::vector<long>& batch_index) {
  if (!quiet_.enabled())
    return dF;
  std::vector<Mat3> increments = dF;  // a quiet point's entry is only booked (zero steps)
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (quiet_.accumulate(points[i], dF[i]))
      increments[i] = quiet_.pending(points[i]);
    else
      batch_index[points[i]] = -1;
  }
  return increments;
}

void DemRveMaterial::settle_quiet_points(const std::vector<std::size_t>& points,
                                         const std::vector<long>& batch_index) {
  if (!quiet_.enabled())
    return;
  for (const std::size_t p : points) {
    if (batch_index[p] >= 0)
      quiet_.after_dem(p, stress_[p]);
    else
      stress_[p] = quiet_.predicted(p);
  }
}

void DemRveMaterial::update(const std::vector<std::size_t>& points, const std::vector<Mat3>& dF,
                            double /*dt*/, std::vector<Mat3>& stress) {
  if (!layout_)
    create_rves();
  ++updates_;
  std::vector<long> batch_index(points_, -1);
  for (std::size_t i = 0; i < points.size(); ++i)
    batch_index[points[i]] = static_cast<long>(i);
  const std::vector<Mat3> increments = dem_increments(points, dF, batch_index);

  // The stresses before the update, the same on every rank (deform_owned overwrites the owned
  // points' entries: taken after it, the low-stress share would depend on the rank count).
  const std::vector<Mat3> before = stress_;
  const std::vector<double> predicted = predict_steps(batch_index, increments);
  rebalance(work_of(predicted, batch_index));
  const double start = MPI_Wtime();
  const std::vector<double> owned = deform_owned(batch_index, increments);
  const double computed = MPI_Wtime();
  // One exchange: stress (9), DEM steps, seconds of every point.
  constexpr int kWidth = 11;
  const std::vector<double> all = layout_->gather(owned, kWidth);
  std::vector<double> seconds(points_);
  for (std::size_t p = 0; p < points_; ++p) {
    stress_[p] = Eigen::Map<const Mat3>(&all[p * kWidth]);
    substeps_[p] = all[p * kWidth + 9];
    seconds[p] = all[p * kWidth + 10];
    if (batch_index[p] >= 0)
      dem_pressure_[p] = mean_pressure(stress_[p], spec_.dimension);  // as Rve::stress()
  }
  settle_quiet_points(points, batch_index);
  for (std::size_t i = 0; i < points.size(); ++i)
    work_.add(points[i], substeps_[points[i]], mean_pressure(before[points[i]], spec_.dimension),
              increments[i]);
  cost_.compute_seconds += computed - start;
  cost_.communication_seconds += MPI_Wtime() - computed;
  account(predicted, seconds, batch_index);
  // Every rank knows every RVE's step count: the total needs no reduction.
  for (const double steps : substeps_)
    cost_.particle_steps += steps * static_cast<double>(spec_.grains);
  for (std::size_t i = 0; i < points.size(); ++i)
    stress[i] = stress_[points[i]];
}

void DemRveMaterial::write_checkpoint(materials::CheckpointWriter& out, std::size_t points) {
  if (!layout_)
    throw std::logic_error(path_ + ": checkpoint before the first update");
  if (points != points_)
    throw std::logic_error(path_ + ": checkpoint of " + std::to_string(points) + " points, not " +
                           std::to_string(points_));
  std::vector<double> owned, index;
  // The group's leader writes its RVEs into one bundle, in point order (docs/hpc.md §3).
  std::unique_ptr<PointBundleWriter> bundle;
  if (!layout_->owned().empty())
    bundle = or_end_job(path_ + ": checkpoint not written (the previous one is kept)", [&] {
      return std::make_unique<PointBundleWriter>(out.folder(), scratch_folder(),
                                                 group_leader_rank(), layout_->group_comm());
    });
  for (const std::size_t p : layout_->owned()) {
    rve::Rve& rve = *rves_[p];
    or_end_job(point_label(p) + ": checkpoint not written (the previous one is kept)",
               [&] { bundle->add(rve, index); });
    PointCheckpoint saved{stress_[p], substeps_[p], rve.state()};
    std::copy(work_.row(p), work_.row(p) + DemWork::kValues, saved.work);
    quiet_.save_row(p, saved.quiet);
    pack(saved, owned);
  }
  const std::string digest =
      bundle ? or_end_job(path_ + ": checkpoint not written (the previous one is kept)",
                          [&] { return bundle->close(); })
             : "";
  record_bundle_digests(out, digest);
  write_points(out, layout_->gather(owned, static_cast<int>(point_checkpoint_width())));
  out.write(kBundleIndexName, layout_->gather(index, static_cast<int>(kPointIndexWidth)));
  out.set(kBundleMembersName, static_cast<double>(kPointMembers));
  out.set("updates", static_cast<double>(updates_));
  out.set("particle_steps", cost_.particle_steps);
  for (const QuietStatField& f : kQuietStatFields)
    out.set(f.name, quiet_.stats().*f.value);
  // Where the RVEs are, so that a resume on as many groups makes the balancer's decisions
  // again; and the stepping totals so far.
  std::vector<double> owners{static_cast<double>(layout_->groups())};
  owners.insert(owners.end(), layout_->owners().begin(), layout_->owners().end());
  out.write(kOwnersName, owners);
  out.write(kSteppingName,
            {predicted_totals_.work, predicted_totals_.makespan, predicted_totals_.bound,
             work_totals_.work, work_totals_.makespan, work_totals_.bound, seconds_totals_.work,
             seconds_totals_.makespan, seconds_totals_.bound, migrations_, rebalances_});
  if (record_)
    or_end_job(path_ + ": the cost record not written", [&] { record_->flush(); });
}

void DemRveMaterial::restore_checkpoint(const materials::CheckpointReader& in,
                                        const std::vector<Mat3>& stress) {
  if (stress.size() != points_)
    throw std::logic_error(path_ + ": restore of " + std::to_string(stress.size()) +
                           " points, not " + std::to_string(points_));
  const std::vector<double> rows = read_points(in, points_);
  const std::vector<double> index =
      in.has(kBundleIndexName) ? in.read(kBundleIndexName) : std::vector<double>();
  if (!index.empty() && index.size() != points_ * kPointIndexWidth)
    throw std::runtime_error(in.describe() + ": the bundle index holds " +
                             std::to_string(index.size() / kPointIndexWidth) +
                             " DEM points, the case has " + std::to_string(points_));
  const double start = MPI_Wtime();
  layout_ = std::make_unique<RveLayout>(comm_, ranks_per_rve_, points_);
  if (in.has(kOwnersName)) {
    // The owners of the checkpoint when the groups are as many; dealt out otherwise.
    const std::vector<double> saved = in.read(kOwnersName);
    if (saved.size() == points_ + 1 && saved[0] == static_cast<double>(layout_->groups()))
      layout_->reassign(std::vector<int>(saved.begin() + 1, saved.end()));
  }
  if (in.has(kSteppingName)) {
    const std::vector<double> t = in.read(kSteppingName);
    if (t.size() == 3 * StepTotals::kValues + 2) {
      predicted_totals_.load(&t[0]);
      work_totals_.load(&t[3]);
      seconds_totals_.load(&t[6]);
      migrations_ = t[9];
      rebalances_ = t[10];
    }
  }
  stress_.resize(points_);
  substeps_.resize(points_);
  dem_pressure_.resize(points_);
  rves_.clear();
  rves_.resize(points_);
  start_work_ledger();
  for (std::size_t p = 0; p < points_; ++p) {
    const PointCheckpoint saved = unpack(rows.data() + p * point_checkpoint_width());
    stress_[p] = saved.stress;
    substeps_[p] = saved.substeps;
    dem_pressure_[p] = saved.rve.last_mean_stress;
    work_.restore_row(p, saved.work);
    quiet_.restore_row(p, saved.quiet);
    if (!layout_->owns(p))
      continue;
    rves_[p] = or_end_job(in.describe() + ": " + point_label(p) + " not restored", [&] {
      // Format 5: the point's byte ranges of its writer's bundle; before, files of its own.
      const std::string file =
          index.empty() ? checkpoint_file(in.folder(), p)
                        : unbundle_point(in.folder(), index.data() + p * kPointIndexWidth,
                                         scratch_folder(), layout_->group_comm());
      return rve::Rve::from_checkpoint(spec_, file, layout_->group_comm(), point_label(p));
    });
    rves_[p]->restore(saved.rve);
  }
  if (!index.empty())
    remove_scratch(scratch_folder(), layout_->group_comm());
  updates_ = static_cast<long>(in.get("updates"));
  QuietStats stats;
  for (const QuietStatField& f : kQuietStatFields)
    stats.*f.value = in.get(f.name);
  quiet_.restore_stats(stats);
  cost_.simulations = points_;
  cost_.particle_steps = in.get("particle_steps");
  start_cost_record(true);
  cost_.preparation_seconds += MPI_Wtime() - start;
}

int DemRveMaterial::group_leader_rank() const {
  return rank_ - rank_ % ranks_per_rve_;
}

std::string DemRveMaterial::scratch_folder() const {
  if (work_dir_.empty())
    throw std::logic_error(path_ + ": no work folder for the checkpoint's scratch files");
  return work_dir_ + "/checkpoint_scratch_rank_" + std::to_string(group_leader_rank());
}

void DemRveMaterial::record_bundle_digests(materials::CheckpointWriter& out,
                                           const std::string& digest) const {
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
}

std::vector<std::string> DemRveMaterial::state_names() const {
  // Which rank group owns a point is not a result (it depends on the rank count): not here.
  return {"dem_substeps", "dem_particle_steps"};
}

double DemRveMaterial::state(std::size_t point, std::size_t k) const {
  if (point >= substeps_.size())
    return 0.0;
  return k == 0 ? substeps_[point] : work_.total(point);
}

void DemRveMaterial::write_snapshot(std::size_t point, const std::string& prefix) {
  if (point >= points_)
    throw std::out_of_range(path_ + ": no material point " + std::to_string(point));
  if (!layout_)
    create_rves();
  if (layout_->owns(point))
    rve::write_snapshot(*rves_[point], prefix, layout_->group_leader());
}

materials::Report DemRveMaterial::report() const {
  materials::Report r = dem_statistics(cost_);
  add_work_shares(r, work_.sum(1), work_.sum(2), work_.sum(3));
  if (layout_)
    add_stepping(r, {static_cast<double>(layout_->groups()), predicted_totals_, work_totals_,
                     seconds_totals_, migrations_, rebalances_, cost_.migration_seconds});
  if (quiet_.quiet_enabled())
    add_quiet_points(r, quiet_.stats());
  if (quiet_.continuum_start_enabled())
    add_continuum_start(r, quiet_.stats(), static_cast<double>(cost_.simulations));
  return r;
}

}  // namespace mpm_lig::coupling
