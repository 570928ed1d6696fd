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

//! Collective over `comm`: every material's prepare() (DEM packings go to `work_dir`). Must
//! come before run_case, which reads densities and wave moduli.
void prepare_materials(MpmCase& c, MPI_Comm comm, const std::string& work_dir,
                       const TestHooks& hooks = {});

//! Runs a validated, prepared case: the gravity stage (if any), then the main stage until the
//! end time or step count, with the Recorder's output when `options.write_results`.
//! `observer` (optional) sees the solver after every main-stage step: tests use it.
//! Returns false if SIGTERM/SIGINT/SIGHUP stopped the run (after writing a checkpoint).
//!
//! Test-only: with options.hooks.kill_at_step = n, rank 0 kills itself with SIGKILL after
//! step n is recorded (the resume-identity test).
template <int D>
bool run_case(MpmCase& c, const RunOptions& options,
              const std::function<void(const Solver<D>&)>& observer = {});

//! The same with results in `directory` only, or no files if it is empty (serial runs, tests).
template <int D>
bool run_case(MpmCase& c, const std::string& directory,
              const std::function<void(const Solver<D>&)>& observer = {}) {
  RunOptions options;
  options.run_dir = directory;
  options.comm = MPI_COMM_SELF;  // one process's run: no collective over other ranks
  return run_case<D>(c, options, observer);
}

//! Steps the main stage will take.
long main_stage_steps(const MpmCase& c, double dt);

}  // namespace mpm_lig::mpm
