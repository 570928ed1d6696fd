#include "coupling/dem_rve_material.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/case_error.h"
#include "dem/file_name.h"
#include "rve/rve.h"

namespace mpm_lig::coupling {
namespace {

rve::RveSpec read_rve(const CaseNode& node) {
  node.get<std::string>("type");
  return rve::parse_rve_spec(node.child("rve"));
}

PackingOrder read_packing_order(const CaseNode& node, const rve::RveSpec& spec) {
  const int count = node.get_or<int>("packings", 1);
  if (count < 1)
    node.fail("packings", "must be >= 1");
  if (!spec.restart_file.empty() && count != 1)
    node.fail("packings", "must be 1 when rve.restart_file gives the packing");
  PackingOrder order;
  order.count = static_cast<std::size_t>(count);
  order.scattered =
      node.choice_or("packing_order", {"cyclic", "scattered"}, "cyclic") == "scattered";
  return order;
}

int read_ranks_per_rve(const CaseNode& node) {
  const int ranks = node.get_or<int>("ranks_per_rve", 1);
  if (ranks < 1)
    node.fail("ranks_per_rve", "must be >= 1");
  return ranks;
}

//! The node `key` read by `parse`, or the defaults (off) when the case has none.
template <class Spec>
Spec read_optional(const CaseNode& node, const char* key, Spec (*parse)(const CaseNode&)) {
  return node.has(key) ? parse(node.child(key)) : Spec{};
}

}  // namespace

DemRveMaterial::DemRveMaterial(const CaseNode& node)
    : spec_(read_rve(node)),
      path_(node.path()),
      packing_order_(read_packing_order(node, spec_)),
      ranks_per_rve_(read_ranks_per_rve(node)),
      selection_(read_optional(node, "quiet", &parse_quiet),
                 read_optional(node, "start_as_continuum", &parse_continuum_start),
                 read_optional(node, "steady_flow", &parse_steady_flow)),
      schedule_(read_optional(node, "balance", &parse_balance), spec_, path_) {}

DemRveMaterial::~DemRveMaterial() = default;

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
  if (points > 0 && packing_order_.count > points)
    throw CaseError(path_ + ".packings", std::to_string(packing_order_.count) + " packings for " +
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
  MPI_Comm_rank(context.comm, &rank_);
  work_dir_ = context.work_dir;
  rves_ = std::make_unique<OwnedRves>(spec_, ranks_per_rve_, PointLabel{path_, rank_}, context);
  packings_ = prepare_packings(spec_, static_cast<int>(packing_order_.count), ranks_per_rve_, path_,
                               context);
  cost_.preparation_seconds += MPI_Wtime() - start;
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

double DemRveMaterial::current_wave_modulus() const {
  double p_max = 0.0;
  for (const Mat3& sigma : results_.stress)
    p_max = std::max(p_max, mean_pressure(sigma, spec_.dimension));
  double m = 0.0;
  for (const Packing& p : packings_) {
    const double probed_at = mean_pressure(p.stress, spec_.dimension);
    const double ratio = probed_at > 0.0 ? std::max(1.0, p_max / probed_at) : 1.0;
    m = std::max(m, p.wave_modulus * std::cbrt(ratio));
  }
  return m;
}

std::size_t DemRveMaterial::add_points(std::size_t count) {
  if (rves_ && rves_->dealt())
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
  return packings_.at(packing_order_.of(point)).stress;
}

void DemRveMaterial::create_rves() {
  if (!rves_)
    throw std::logic_error(path_ + ": RVEs before prepare()");
  const double start = MPI_Wtime();
  rves_->deal(points_);
  results_.start(points_);
  for (std::size_t p = 0; p < points_; ++p)
    results_.stress[p] = initial_stress(p);
  rves_->clone(packings_, packing_order_);
  start_ledgers();
  schedule_.start_record(rank_, work_dir_, points_, false, updates_);
  cost_.simulations = points_;
  cost_.preparation_seconds += MPI_Wtime() - start;
}

void DemRveMaterial::start_ledgers() {
  // A packing read from a restart file has no preparation pressure: its own stress stands in.
  double p = spec_.preparation.confining_pressure;
  if (p <= 0.0 && !packings_.empty())
    p = mean_pressure(packings_.front().stress, spec_.dimension);
  work_.start(points_, static_cast<double>(spec_.grains),
              spec_.substeps.fixed > 0 ? 0 : spec_.substeps.max, p);
  selection_.start(points_, spec_.dimension, spec_.substeps.pressure_floor, packings_,
                   packing_order_);
}

void DemRveMaterial::update(const materials::MaterialStep& step, std::vector<Mat3>& stress) {
  if (!rves_ || !rves_->dealt())
    create_rves();
  ++updates_;
  const DemBatch batch = selection_.select(points_, step);
  // The stresses before the update, the same on every rank (the gather overwrites them).
  const std::vector<Mat3> before = results_.stress;
  const std::vector<double> predicted =
      schedule_.predict_steps(batch, results_.dem_pressure, results_.net_shear);
  // rve.setup_every: every RVE sets up at the first update of each period, and only there may
  // RVEs move between ranks (a moved RVE's engine is new and must set up): which RVE moved,
  // and when, then changes no result.
  const bool period_start = rve::starts_setup_period(spec_, updates_ - 1);
  if (period_start)
    rebalance(predicted, batch);
  const rve::Rve::EngineRun run = rve::update_engine_run(spec_);
  const double start = MPI_Wtime();
  const std::vector<double> owned =
      rves_->deform(batch, results_.stress, updates_, run, period_start);
  const double computed = MPI_Wtime();
  const std::vector<double> seconds =
      gather_results(rves_->layout(), owned, batch, spec_.dimension, results_);
  selection_.settle(step.points, batch, results_.stress);
  for (std::size_t i = 0; i < step.points.size(); ++i) {
    const std::size_t p = step.points[i];
    work_.add(p, results_.substeps[p], mean_pressure(before[p], spec_.dimension),
              batch.increments[i]);
  }
  cost_.compute_seconds += computed - start;
  cost_.communication_seconds += MPI_Wtime() - computed;
  schedule_.account(updates_, rves_->layout(), predicted, results_.substeps, seconds, batch);
  // Every rank knows every RVE's step count: the total needs no reduction.
  for (const double steps : results_.substeps)
    cost_.particle_steps += steps * static_cast<double>(spec_.grains);
  stress.resize(step.points.size());
  for (std::size_t i = 0; i < step.points.size(); ++i)
    stress[i] = results_.stress[step.points[i]];
}

void DemRveMaterial::rebalance(const std::vector<double>& predicted_steps, const DemBatch& batch) {
  const BalancePlan plan = schedule_.plan(predicted_steps, batch, rves_->layout());
  if (plan.moves == 0)
    return;
  const double start = MPI_Wtime();
  rves_->migrate(plan.owner);
  cost_.migration_seconds += MPI_Wtime() - start;
  schedule_.count_moves(plan.moves);
}

std::vector<std::string> DemRveMaterial::state_names() const {
  // Which rank group owns a point is not a result (it depends on the rank count): not here.
  return {"dem_substeps", "dem_particle_steps"};
}

double DemRveMaterial::state(std::size_t point, std::size_t k) const {
  if (point >= results_.substeps.size())
    return 0.0;
  return k == 0 ? results_.substeps[point] : work_.total(point);
}

void DemRveMaterial::write_snapshot(std::size_t point, const std::string& prefix) {
  if (point >= points_)
    throw std::out_of_range(path_ + ": no material point " + std::to_string(point));
  if (!rves_ || !rves_->dealt())
    create_rves();
  rves_->write_snapshot(point, prefix);
}

materials::Report DemRveMaterial::report() const {
  materials::Report r = dem_statistics(cost_);
  add_work_shares(r, work_.sum(1), work_.sum(2), work_.sum(3));
  if (rves_ && rves_->dealt())
    add_stepping(r, schedule_.stepping(rves_->layout(), cost_.migration_seconds));
  const QuietPoints& quiet = selection_.quiet();
  if (quiet.quiet_enabled())
    add_quiet_points(r, quiet.stats());
  if (quiet.continuum_start_enabled())
    add_continuum_start(r, quiet.stats(), static_cast<double>(cost_.simulations));
  if (selection_.flow().enabled())
    add_steady_flow(r, selection_.flow().stats());
  return r;
}

}  // namespace mpm_lig::coupling
