#include "coupling/rve_schedule.h"

#include <filesystem>

#include "coupling/job_failure.h"
#include "rve/rve.h"

namespace mpm_lig::coupling {
namespace {

constexpr const char* kOwnersName = "rve_owner";   // groups, then every point's group
constexpr const char* kSteppingName = "stepping";  // StepTotals ×3, migrations, rebalances

}  // namespace

std::vector<double> RveSchedule::predict_steps(const DemBatch& batch,
                                               const std::vector<double>& dem_pressure,
                                               const std::vector<double>& net_shear) const {
  std::vector<double> steps(dem_pressure.size(), 0.0);
  for (std::size_t p = 0; p < steps.size(); ++p) {
    if (batch.runs(p))
      steps[p] = rve::predicted_substeps(rve_, batch.increment(p), dem_pressure[p], net_shear[p]);
  }
  return steps;
}

std::vector<double> RveSchedule::work_of(const std::vector<double>& steps,
                                         const DemBatch& batch) const {
  std::vector<double> work(steps.size(), 0.0);
  for (std::size_t p = 0; p < work.size(); ++p) {
    if (batch.runs(p))
      work[p] = (steps[p] + balance_.update_cost) * static_cast<double>(rve_.grains);
  }
  return work;
}

double RveSchedule::fewest_substeps() const {
  return rve_.substeps.fixed > 0 ? rve_.substeps.fixed : rve_.substeps.min;
}

BalancePlan RveSchedule::plan(const std::vector<double>& predicted_steps, const DemBatch& batch,
                              const RveLayout& layout) const {
  if (!balance_.enabled || layout.groups() < 2)
    return BalancePlan{};
  // Replicated costs and owners only: every rank plans the same moves, and so does a resume.
  // (With rank_speed "measured" the groups' speeds too: the same on every rank, gathered.)
  // What stays of a point's cost is its update at the fewest sub-steps: the peaks above it
  // move on with the deformation (balance.persistence; plan_moves caps it at each cost).
  const double grains = static_cast<double>(rve_.grains);
  const std::vector<double> floor(predicted_steps.size(),
                                  (fewest_substeps() + balance_.update_cost) * grains);
  return plan_moves(work_of(predicted_steps, batch), layout.owners(), layout.groups(),
                    balance_.threshold, balance_.horizon, balance_.move_cost * grains,
                    speed_ ? speed_->slowness() : std::vector<double>(), floor,
                    balance_.persistence);
}

void RveSchedule::count_moves(std::size_t moves) {
  migrations_ += static_cast<double>(moves);
  rebalances_ += 1.0;
}

void RveSchedule::account(long update, const RveLayout& layout,
                          const std::vector<double>& predicted_steps,
                          const std::vector<double>& substeps, const std::vector<double>& seconds,
                          const DemBatch& batch) {
  const std::vector<int>& owners = layout.owners();
  const int groups = layout.groups();
  predicted_totals_.add(work_of(predicted_steps, batch), owners, groups);
  const std::vector<double> work = work_of(substeps, batch);
  work_totals_.add(work, owners, groups);
  seconds_totals_.add(seconds, owners, groups);
  if (balance_.measured_speed) {
    if (!speed_)
      speed_ = std::make_unique<GroupSpeed>(groups);
    speed_->observe(work, seconds, owners);
  }
  if (!record_)
    return;
  record_->add(update, groups, predicted_steps, substeps, seconds, owners);
  if (record_->buffered() >= 100)
    flush_record();
}

void RveSchedule::start_record(int rank, const std::string& work_dir, std::size_t points,
                               bool resumed, long updates) {
  if (rank != 0 || work_dir.empty())
    return;
  record_ = std::make_unique<CostRecord>(work_dir + "/cost_record.h5", points,
                                         static_cast<double>(rve_.grains), balance_.update_cost,
                                         fewest_substeps());
  or_end_job(path_ + ": the cost record not started", [&] {
    std::filesystem::create_directories(work_dir);
    if (resumed)
      record_->continue_after(updates);
    else
      record_->create();
  });
}

void RveSchedule::flush_record() {
  if (record_)
    or_end_job(path_ + ": the cost record not written", [&] { record_->flush(); });
}

void RveSchedule::write_checkpoint(materials::CheckpointWriter& out,
                                   const RveLayout& layout) const {
  std::vector<double> owners{static_cast<double>(layout.groups())};
  owners.insert(owners.end(), layout.owners().begin(), layout.owners().end());
  out.write(kOwnersName, owners);
  out.write(kSteppingName,
            {predicted_totals_.work, predicted_totals_.makespan, predicted_totals_.bound,
             work_totals_.work, work_totals_.makespan, work_totals_.bound, seconds_totals_.work,
             seconds_totals_.makespan, seconds_totals_.bound, migrations_, rebalances_});
}

void RveSchedule::restore_checkpoint(const materials::CheckpointReader& in, RveLayout& layout) {
  if (in.has(kOwnersName)) {
    // The owners of the checkpoint when the groups are as many; dealt out otherwise.
    const std::vector<double> saved = in.read(kOwnersName);
    if (saved.size() == layout.rve_count() + 1 && saved[0] == static_cast<double>(layout.groups()))
      layout.reassign(std::vector<int>(saved.begin() + 1, saved.end()));
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
}

SteppingCounters RveSchedule::stepping(const RveLayout& layout, double migration_seconds) const {
  return {static_cast<double>(layout.groups()),
          predicted_totals_,
          work_totals_,
          seconds_totals_,
          migrations_,
          rebalances_,
          migration_seconds};
}

}  // namespace mpm_lig::coupling
