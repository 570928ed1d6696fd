#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "core/tensor.h"
#include "core/test_hooks.h"
#include "coupling/job_failure.h"
#include "coupling/packings.h"
#include "coupling/point_selection.h"
#include "coupling/rve_layout.h"
#include "materials/checkpoint_io.h"
#include "materials/material.h"
#include "rve/rve.h"
#include "rve/spec.h"

namespace mpm_lig::coupling {

//! The RVEs of a dem_rve material's points that this rank's group runs, and where every RVE
//! is (RveLayout): cloned from their packings, deformed, moved between groups, saved into the
//! group's checkpoint bundle and read back from it.
//!
//! Only this part touches the engines at an update; an engine failure of one of its RVEs ends
//! the whole job at once, naming the point (the other ranks are about to wait for this one).
//!
//! Test-only fault injection (MaterialContext::hooks, from MPM_LIG_FAULT_POINT=i and
//! MPM_LIG_FAULT_UPDATE=u at start-up): the rank that owns point i sends its engine an unknown
//! command at update u; the engine's own error path must end the whole job naming the point
//! and its rank.
class OwnedRves {
 public:
  //! RVEs of `spec` on groups of `ranks_per_rve` ranks of `context.comm`, their files under
  //! `context.work_dir`, points named by `label`.
  OwnedRves(const rve::RveSpec& spec, int ranks_per_rve, PointLabel label,
            const materials::MaterialContext& context);
  //! Removes the (empty) folder moving RVEs pass through.
  ~OwnedRves();
  OwnedRves(const OwnedRves&) = delete;
  OwnedRves& operator=(const OwnedRves&) = delete;

  //! Collective: `points` RVEs dealt to the rank groups (RveLayout), none created yet.
  void deal(std::size_t points);
  bool dealt() const { return layout_ != nullptr; }
  //! Collective: every owned point's RVE cloned from its packing (`order`).
  void clone(const std::vector<Packing>& packings, const PackingOrder& order);
  const RveLayout& layout() const { return *layout_; }
  RveLayout& layout() { return *layout_; }

  //! Collective over each group: the owned RVEs that run in `batch` deformed by their
  //! increments at MPM update `update`; per owned point its row (point_results.h): the new
  //! stress (its `stress` entry when it ran none), DEM steps and seconds. `run`: how each runs
  //! its engine; `set_up`: every owned RVE (running now or not) sets up at its next update.
  std::vector<double> deform(const DemBatch& batch, const std::vector<Mat3>& stress, long update,
                             rve::Rve::EngineRun run, bool set_up);
  //! Collective: every point to group `owners[point]`. A moving RVE goes through its checkpoint
  //! files and its Rve::State; the new owner continues it bit-identically.
  void migrate(const std::vector<int>& owners);

  //! Collective: every group's RVEs into one bundle `rank_<r>.bundle` in out.folder() (r: the
  //! group leader's rank; point_bundle.h), every bundle's digest recorded in `out`. Returns the
  //! owned points' index values (kPointIndexWidth each, in owned() order).
  std::vector<double> write_bundle(materials::CheckpointWriter& out);
  //! Collective over the group: owned `point` from checkpoint `in` with `state`: out of its
  //! writer's bundle (`index`: its kPointIndexWidth values) or, with no index (format 4), from
  //! a file of its own.
  void restore(std::size_t point, const materials::CheckpointReader& in, const double* index,
               const rve::Rve::State& state);
  //! Collective over the group: after the last restore() from bundles, its scratch removed.
  void finish_restore();
  //! The state of an owned point's RVE.
  rve::Rve::State state(std::size_t point) const { return rves_[point]->state(); }

  //! Collective: `point`'s microstructure as PREFIX_{grains,contacts,cell}.vtk (its group).
  void write_snapshot(std::size_t point, const std::string& prefix);

 private:
  void inject_fault_if_asked(std::size_t point, rve::Rve& rve, long update) const;
  //! The rank (in the run) of this rank's group leader: it writes the group's bundle.
  int group_leader_rank() const;
  //! The group's scratch folder for the files the engines write and read (under work_dir_).
  std::string scratch_folder() const;

  rve::RveSpec spec_;
  int ranks_per_rve_ = 1;
  PointLabel label_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::string work_dir_;
  TestHooks hooks_;
  std::unique_ptr<RveLayout> layout_;
  std::vector<std::unique_ptr<rve::Rve>> rves_;  //!< by point; null where another group owns it
};

}  // namespace mpm_lig::coupling
