#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "coupling/cost_record.h"
#include "coupling/dem_statistics.h"
#include "coupling/point_selection.h"
#include "coupling/rve_balance.h"
#include "coupling/rve_layout.h"
#include "materials/checkpoint_io.h"
#include "rve/spec.h"

namespace mpm_lig::coupling {

//! When and where a dem_rve material's RVEs run: every point's predicted cost of the coming
//! update, the balancer's moves (rve_balance.h), and what every update cost (the stepping
//! totals, the groups' speeds, the cost record). Costs, owners and parameters are replicated,
//! so every rank plans the same moves without a message (docs/DESIGN.md §7).
class RveSchedule {
 public:
  //! For RVEs of `rve` in the material at case path `path`.
  RveSchedule(const BalanceSpec& balance, const rve::RveSpec& rve, std::string path)
      : balance_(balance), rve_(rve), path_(std::move(path)) {}

  //! Every point's predicted DEM steps of this update (0 for those that run none), from the
  //! mean stress each RVE last measured and its net shear.
  std::vector<double> predict_steps(const DemBatch& batch, const std::vector<double>& dem_pressure,
                                    const std::vector<double>& net_shear) const;
  //! The moves that pay before this update (plan.moves 0: none; always when balancing is off
  //! or there is one group).
  BalancePlan plan(const std::vector<double>& predicted_steps, const DemBatch& batch,
                   const RveLayout& layout) const;
  //! Book `moves` RVEs moved before an update.
  void count_moves(std::size_t moves);
  //! One update's predicted and measured steps and seconds of every point (`layout` the
  //! owners that ran them): the stepping totals, the groups' speeds, the cost record.
  void account(long update, const RveLayout& layout, const std::vector<double>& predicted_steps,
               const std::vector<double>& substeps, const std::vector<double>& seconds,
               const DemBatch& batch);

  //! Rank 0 with a work folder: the cost record `work_dir`/cost_record.h5 of `points` points,
  //! new, or continued after update `updates` of a resumed run.
  void start_record(int rank, const std::string& work_dir, std::size_t points, bool resumed,
                    long updates);
  //! The buffered rows of the cost record appended to its file (rank 0).
  void flush_record();

  //! Checkpoint: where every RVE is (so that a resume on as many groups makes the balancer's
  //! decisions again) and the stepping totals so far.
  void write_checkpoint(materials::CheckpointWriter& out, const RveLayout& layout) const;
  //! The owners of `in` given to `layout` when it has as many groups (dealt otherwise), and
  //! the stepping totals.
  void restore_checkpoint(const materials::CheckpointReader& in, RveLayout& layout);
  //! The stepping counters for the report.
  SteppingCounters stepping(const RveLayout& layout, double migration_seconds) const;

 private:
  //! The work of the points in particle-steps, an update's fixed cost included.
  std::vector<double> work_of(const std::vector<double>& steps, const DemBatch& batch) const;
  //! The sub-steps of an update at the least (substeps.fixed, or substeps.min).
  double fewest_substeps() const;

  BalanceSpec balance_;
  rve::RveSpec rve_;
  std::string path_;
  std::unique_ptr<GroupSpeed> speed_;   //!< with rank_speed "measured"; not checkpointed (timings)
  std::unique_ptr<CostRecord> record_;  //!< rank 0's
  StepTotals predicted_totals_, work_totals_, seconds_totals_;
  double migrations_ = 0.0;
  double rebalances_ = 0.0;
};

}  // namespace mpm_lig::coupling
