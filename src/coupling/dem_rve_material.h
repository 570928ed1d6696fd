#pragma once

#include <memory>
#include <string>
#include <vector>

#include "coupling/dem_statistics.h"
#include "coupling/dem_work.h"
#include "coupling/owned_rves.h"
#include "coupling/packings.h"
#include "coupling/point_results.h"
#include "coupling/point_selection.h"
#include "coupling/rve_schedule.h"
#include "materials/material.h"
#include "rve/spec.h"

namespace mpm_lig::coupling {

//! The material law of a point is its own DEM packing (the "dem_rve" material).
//!
//! Case node: {"type": "dem_rve", "rve": {RVE spec}, "packings": K, "packing_order":
//! "cyclic"|"scattered", "ranks_per_rve": g, "quiet": {QuietSpec}, "start_as_continuum":
//! {ContinuumStartSpec}, "steady_flow": {SteadyFlowSpec}, "balance": {BalanceSpec}}.
//! `prepare()` consolidates K packings (seeds rve.seed + k) or takes `rve.restart_file`;
//! point i is cloned from packing PackingOrder::of(i). The MPM is replicated on every rank, so
//! every rank calls update() with the same batch. An update goes through its parts in order:
//! PointSelection (which points run DEM: quiet points), RveSchedule (predicted costs, the
//! balancer's moves, the cost record), OwnedRves (this rank group's RVEs deformed, moved,
//! saved), gather_results (the owners' stresses to every rank in point order, PointResults);
//! this class only orchestrates them and keeps the counters (DemWork, DemCost).
class DemRveMaterial final : public materials::Material, public materials::MicrostructureSnapshots {
 public:
  //! Validates the whole node; creates nothing.
  explicit DemRveMaterial(const CaseNode& node);
  ~DemRveMaterial() override;

  std::string type() const override { return "dem_rve"; }
  //! Collective: consolidate the packings into `context.work_dir` (or load rve.restart_file).
  void prepare(const materials::MaterialContext& context) override;
  void check_dimension(const CaseNode& node, int dimension) const override;
  //! Rank groups, packings against points, engine file names under `run_dir`, RVE memory.
  void check_run(std::size_t points, int ranks, const std::string& run_dir,
                 MemoryBudget& budget) const override;
  double density() const override;
  double wave_modulus() const override;
  //! The probed modulus times (p_max / p_probe)^(1/3), p_max the largest mean stress of the
  //! points: Hertz contacts stiffen a packing so (measured: docs/methods.md §7).
  double current_wave_modulus() const override;
  //! Measured (docs/testing.md, Hard cases): a DEM-backed column is stable up to 0.5 times the
  //! CFL step of its probed modulus, departs at 0.55 and is wrong from 0.6 on.
  double max_cfl() const override { return 0.5; }
  std::size_t add_points(std::size_t count) override;
  void set_stress(std::size_t point, const Mat3& sigma) override;
  //! Stress of `point` before any deformation (its packing's).
  Mat3 initial_stress(std::size_t point) const override;
  void update(const materials::MaterialStep& step, std::vector<Mat3>& stress) override;
  std::vector<std::string> state_names() const override;
  double state(std::size_t point, std::size_t k) const override;
  bool accepts_initial_stress() const override { return false; }
  //! Its checkpoint holds every RVE (write_checkpoint / restore_checkpoint).
  bool checkpointable() const override { return true; }
  //! With rve.setup_every > 1: after the last update of a period (the next one sets up).
  bool at_exact_checkpoint() const override { return rve::starts_setup_period(spec_, updates_); }
  void write_snapshot(std::size_t point, const std::string& prefix) override;
  //! dem_statistics() of its counters; the work shares; "stepping" once its RVEs are made;
  //! "quiet_points", "start_as_continuum" and "steady_flow" where the case asks for them.
  materials::Report report() const override;

  //! Collective: every group writes its RVEs into `rank_<r>.bundle` in out.folder() (r: the
  //! group leader's rank; point_bundle.h), the index of every point's members and every
  //! point's named fields (PointCheckpoint) go to `out`. Only after the first update.
  void write_checkpoint(materials::CheckpointWriter& out, std::size_t points) override;
  //! Collective: the RVEs again from the checkpoint, before any update: from the bundles
  //! (any rank count) or, in a checkpoint of format 4, from point_<i>.restart files.
  void restore_checkpoint(const materials::CheckpointReader& in,
                          const std::vector<Mat3>& stress) override;
  //! update() calls so far (MPM steps).
  long updates() const { return updates_; }

  //! The prepared packings (after prepare()).
  const std::vector<Packing>& packings() const { return packings_; }
  const rve::RveSpec& spec() const { return spec_; }

 private:
  //! Collective: the RVEs dealt and cloned from their packings, before the first update.
  void create_rves();
  //! The work ledger and the quiet points of every point, from the packings.
  void start_ledgers();
  //! Move RVEs to other groups when the predicted costs say it pays (collective).
  void rebalance(const std::vector<double>& predicted_steps, const DemBatch& batch);

  rve::RveSpec spec_;
  std::string path_;
  PackingOrder packing_order_;
  int ranks_per_rve_ = 1;
  int rank_ = 0;
  std::string work_dir_;

  std::vector<Packing> packings_;
  std::size_t points_ = 0;
  PointSelection selection_;         //!< which points run DEM (all ranks)
  RveSchedule schedule_;             //!< costs, balance, cost record (all ranks)
  std::unique_ptr<OwnedRves> rves_;  //!< this group's RVEs; from prepare() on
  PointResults results_;             //!< every point's gathered results (all ranks)
  DemWork work_;                     //!< every point's DEM work (all ranks)
  long updates_ = 0;
  DemCost cost_;
};

}  // namespace mpm_lig::coupling
