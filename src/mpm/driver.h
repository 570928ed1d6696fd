#pragma once

#include <functional>
#include <string>

#include <mpi.h>

#include "core/test_hooks.h"
#include "mpm/case_spec.h"
#include "mpm/solver.h"

namespace mpm_lig::mpm {

//! Where and what run_case writes.
struct RunOptions {
  //! The run's one folder: history.csv, results.h5/.xdmf, summary.json, checkpoints/,
  //! rve_snapshots/. Empty: no files at all.
  std::string run_dir;
  //! Whether this rank writes the result files and progress (rank 0 of a run).
  bool write_results = true;
  //! Checkpoints (every case.checkpoint_every steps and on SIGTERM/SIGINT/SIGHUP) and RVE
  //! snapshots, on every rank's behalf: a run from the command line.
  bool checkpoints = false;
  bool resume = false;         //!< continue from the last checkpoint in run_dir
  int ranks = 1;               //!< MPI ranks of the run (for the summary)
  double prior_seconds = 0.0;  //!< wall time spent before run_case (material preparation)
  MPI_Comm comm = MPI_COMM_WORLD;
  TestHooks hooks;  //!< test-only: hooks.kill_at_step (see run_case)
};

//! Collective over `comm`: every material's prepare() (DEM packings go to `work_dir`/m<id>).
//! The order of a run: read_case → prepare_materials → run_case (which builds the Solver).
void prepare_materials(MpmProblem& problem, MPI_Comm comm, const std::string& work_dir,
                       const TestHooks& hooks = {});

//! Runs a validated case with prepared materials: the gravity stage (if any), then the main
//! stage until the end time or step count, with the Recorder's output when
//! `options.write_results`.
//! `observer` (optional) sees the solver after every main-stage step: tests use it.
//! Returns false if SIGTERM/SIGINT/SIGHUP stopped the run (after writing a checkpoint).
//!
//! Test-only: with options.hooks.kill_at_step = n, rank 0 kills itself with SIGKILL after
//! step n is recorded (the resume-identity test).
template <int D>
bool run_case(MpmProblem problem, const RunOptions& options,
              const std::function<void(const Solver<D>&)>& observer = {});

//! The same with results in `directory` only, or no files if it is empty (serial runs, tests);
//! materials not prepared yet are prepared here, on this process alone (DEM packings in
//! `directory`/packings).
template <int D>
bool run_case(MpmProblem problem, const std::string& directory,
              const std::function<void(const Solver<D>&)>& observer = {}) {
  if (!problem.materials.prepared())
    prepare_materials(problem, MPI_COMM_SELF, (directory.empty() ? "." : directory) + "/packings");
  RunOptions options;
  options.run_dir = directory;
  options.comm = MPI_COMM_SELF;  // one process's run: no collective over other ranks
  return run_case<D>(std::move(problem), options, observer);
}

//! Steps the main stage will take.
long main_stage_steps(const MpmCase& c, double dt);

}  // namespace mpm_lig::mpm
