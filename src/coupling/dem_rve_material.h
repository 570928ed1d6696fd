#pragma once

#include <memory>
#include <string>
#include <vector>

#include "coupling/cost_record.h"
#include "coupling/dem_statistics.h"
#include "coupling/dem_work.h"
#include "coupling/quiet_points.h"
#include "coupling/rve_balance.h"
#include "coupling/rve_layout.h"
#include "materials/material.h"
#include "rve/rve.h"
#include "rve/spec.h"

namespace mpm_lig::coupling {

//! One prepared packing that material points are cloned from.
struct Packing {
  std::string restart_file;    //!< engine restart (contact history included)
  Mat3 stress = Mat3::Zero();  //!< its homogenised stress, physical frame
  double void_ratio = 0.0;
  double wave_modulus = 0.0;     //!< measured constrained modulus [Pa]
  double lateral_modulus = 0.0;  //!< measured lateral stress change per axial strain [Pa]
};

//! The material law of a point is its own DEM packing (the "dem_rve" material).
//!
//! Case node: {"type": "dem_rve", "rve": {RVE spec}, "packings": K, "ranks_per_rve": g,
//! "quiet": {QuietSpec}, "start_as_continuum": {ContinuumStartSpec}, "balance": {BalanceSpec}}.
//! `prepare()` consolidates K packings (seeds rve.seed + k) or takes `rve.restart_file`;
//! point i is cloned from packing i mod K. The MPM is replicated on every rank, so every
//! rank calls update() with the same batch; each rank group deforms the RVEs it owns and
//! the stresses are gathered to all ranks in point order (RveLayout). Before an update the
//! balancer may move RVEs between groups by their predicted costs (rve_balance.h); a move
//! goes through the checkpoint files of the RVE, so results do not depend on it. Every
//! update's costs go to the cost record (cost_record.h).
//!
//! Test-only fault injection (MaterialContext::hooks, from MPM_LIG_FAULT_POINT=i and
//! MPM_LIG_FAULT_UPDATE=u at start-up): the rank that owns point i sends its engine an unknown
//! command at update u; the engine's own error path must end the whole job naming the point
//! and its rank.
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
  //! Measured (docs/testing.md, Hard cases): a DEM-backed column is stable up to 0.5 times the
  //! CFL step of its probed modulus, departs at 0.55 and is wrong from 0.6 on.
  double max_cfl() const override { return 0.5; }
  std::size_t add_points(std::size_t count) override;
  void set_stress(std::size_t point, const Mat3& sigma) override;
  //! Stress of `point` before any deformation (its packing's).
  Mat3 initial_stress(std::size_t point) const override;
  void update(const std::vector<std::size_t>& points, const std::vector<Mat3>& dF, double dt,
              std::vector<Mat3>& stress) override;
  std::vector<std::string> state_names() const override;
  double state(std::size_t point, std::size_t k) const override;
  bool accepts_initial_stress() const override { return false; }
  //! Its checkpoint holds every RVE (write_checkpoint / restore_checkpoint).
  bool checkpointable() const override { return true; }
  void write_snapshot(std::size_t point, const std::string& prefix) override;
  //! dem_statistics() of its counters; the work shares; "stepping" once its RVEs are made;
  //! "quiet_points" and "start_as_continuum" where the case asks for them.
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
  //! Packing k, generated and consolidated (saved to `file`) or loaded from the case's
  //! restart file, on the ranks of `group_comm`. Throws StopRequested when they agree to stop.
  Packing prepare_packing(std::size_t k, const std::string& file, MPI_Comm group_comm) const;
  void create_rves();
  void start_work_ledger();
  //! The increments the RVEs run this update: dF itself, or with quiet points the increments
  //! accumulated by the points that must run DEM now (the others get batch_index -1).
  std::vector<Mat3> dem_increments(const std::vector<std::size_t>& points,
                                   const std::vector<Mat3>& dF, std::vector<long>& batch_index);
  //! After the stresses are gathered: checks and predicted stresses of the quiet points.
  void settle_quiet_points(const std::vector<std::size_t>& points,
                           const std::vector<long>& batch_index);
  //! Deform the owned RVEs; per owned point its stress (9), DEM steps and seconds.
  std::vector<double> deform_owned(const std::vector<long>& batch_index,
                                   const std::vector<Mat3>& dF);
  //! Every point's predicted DEM steps of this update (0 for those that run none).
  std::vector<double> predict_steps(const std::vector<long>& batch_index,
                                    const std::vector<Mat3>& increments) const;
  //! The work of the points in particle-steps, an update's fixed cost included.
  std::vector<double> work_of(const std::vector<double>& steps,
                              const std::vector<long>& batch_index) const;
  //! The sub-steps of an update at the least (substeps.fixed, or substeps.min).
  double fewest_substeps() const;
  //! Move RVEs to other groups when the predicted costs say it pays (collective).
  void rebalance(const std::vector<double>& predicted_work);
  //! Give every point to `owners[point]`, moving the RVEs that change group (collective).
  void migrate(const std::vector<int>& owners);
  void account(const std::vector<double>& predicted_steps, const std::vector<double>& seconds,
               const std::vector<long>& batch_index);
  void start_cost_record(bool resumed);
  void inject_fault_if_asked(std::size_t point, rve::Rve& rve) const;
  std::size_t packing_of(std::size_t point) const { return point % packings_.size(); }
  std::string point_label(std::size_t point) const;
  //! The rank (in the run) of this rank's group leader: it writes the group's bundle.
  int group_leader_rank() const;
  //! The group's scratch folder for the files the engines write and read (under work_dir_).
  std::string scratch_folder() const;
  //! Collective: every bundle's SHA-256 (`digest`: this rank's, or "") goes to out.
  void record_bundle_digests(materials::CheckpointWriter& out, const std::string& digest) const;

  rve::RveSpec spec_;
  std::string path_;
  int packing_count_ = 1;
  int ranks_per_rve_ = 1;

  MPI_Comm comm_ = MPI_COMM_NULL;
  TestHooks hooks_;
  std::vector<Packing> packings_;
  std::size_t points_ = 0;
  std::unique_ptr<RveLayout> layout_;
  std::vector<std::unique_ptr<rve::Rve>> rves_;  //!< by point; null where another group owns it
  std::vector<Mat3> stress_;                     //!< every point's last stress (all ranks)
  std::vector<double> substeps_;                 //!< every point's last DEM step count
  std::vector<double> dem_pressure_;  //!< every RVE's mean stress as it knows it (Rve::State)
  DemWork work_;                      //!< every point's DEM work (all ranks)
  QuietSpec quiet_spec_;
  ContinuumStartSpec continuum_start_spec_;
  QuietPoints quiet_;  //!< every point's quiet state (all ranks)
  BalanceSpec balance_spec_;
  std::unique_ptr<GroupSpeed> speed_;  //!< with rank_speed "measured"; not checkpointed (timings)
  std::string work_dir_;
  std::unique_ptr<CostRecord> record_;  //!< rank 0's
  StepTotals predicted_totals_, work_totals_, seconds_totals_;
  double migrations_ = 0.0;
  double rebalances_ = 0.0;
  long updates_ = 0;
  int rank_ = 0;
  DemCost cost_;
};

}  // namespace mpm_lig::coupling
