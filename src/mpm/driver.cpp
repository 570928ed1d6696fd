#include "mpm/driver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/case_error.h"
#include "core/resources.h"
#include "core/stop_signal.h"

#include "mpm/checkpoint.h"
#include "mpm/checkpoint_folder.h"
#include "mpm/recorder.h"
#include "mpm/rve_snapshots.h"

namespace mpm_lig::mpm {
namespace {

//! A new run in a folder that holds an earlier run's checkpoint: that checkpoint goes, so that
//! a later --resume cannot continue it with this run's files. Only what a run writes there
//! (`latest`, step_<n> folders with their manifest) is removed; anything else stays.
void start_fresh_checkpoints(const std::string& run_dir, MPI_Comm comm) {
  namespace fs = std::filesystem;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const fs::path root = CheckpointFolder::root(run_dir);
  if (rank == 0 && fs::is_directory(root)) {
    std::vector<fs::path> ours;
    for (const fs::directory_entry& e : fs::directory_iterator(root)) {
      const std::string name = e.path().filename().string();
      const bool pointer = (name == "latest" || name == "latest.tmp") && !e.is_directory();
      const bool step = CheckpointFolder::is_step_name(name) && !e.is_symlink() &&
                        e.is_directory() && fs::exists(e.path() / CheckpointFolder::kManifest);
      if (pointer || step)
        ours.push_back(e.path());
    }
    for (const fs::path& p : ours)
      fs::remove_all(p);
    if (fs::is_empty(root))
      fs::remove(root);
  }
  MPI_Barrier(comm);
}

//! A resumed run owns its folder (the application holds its lock): step folders other than the
//! one `latest` names are what a write killed before its commit left (or the previous
//! checkpoint a kill spared between the commit and its removal); they go, so that disk space
//! is not lost to them and nobody mistakes them for checkpoints.
void remove_stale_checkpoints(const std::string& run_dir, MPI_Comm comm) {
  namespace fs = std::filesystem;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const fs::path root = CheckpointFolder::root(run_dir);
  const std::string latest = CheckpointFolder::latest_name_or_empty(run_dir);
  if (rank == 0 && !latest.empty() && fs::is_directory(root)) {
    std::vector<fs::path> stale;
    for (const fs::directory_entry& e : fs::directory_iterator(root)) {
      const std::string name = e.path().filename().string();
      if (CheckpointFolder::is_step_name(name) && name != latest && !e.is_symlink() &&
          e.is_directory())
        stale.push_back(e.path());
    }
    for (const fs::path& p : stale) {
      fs::remove_all(p);
      std::printf("removed %s: a checkpoint write that did not finish\n", p.string().c_str());
    }
    if (fs::exists(root / "latest.tmp"))
      fs::remove(root / "latest.tmp");
    std::fflush(stdout);
  }
  MPI_Barrier(comm);
}

//! The gravity stage (initial stresses by damped dynamic relaxation): no checkpoint is written
//! before the main stage starts, so a stop here leaves no results.
template <int D>
void run_gravity_stage(Solver<D>& solver, const MpmCase& c, MPI_Comm comm) {
  solver.set_gravity_stage(true, c.gravity_stage_damping);
  for (long k = 0; k < c.gravity_stage_steps; ++k) {
    if (stop_requested(comm))
      throw StopRequested("stopped by a signal in the gravity stage (step " + std::to_string(k) +
                          " of " + std::to_string(c.gravity_stage_steps) +
                          "): no results and no checkpoint were written (checkpoints start "
                          "with the main stage)");
    solver.step();
  }
  solver.begin_main_stage();
}

}  // namespace

long main_stage_steps(const MpmCase& c, double dt) {
  if (c.end_steps > 0)
    return c.end_steps;
  // The last step may overshoot the end time by less than one step.
  const double steps = std::ceil(c.end_time / dt - 1e-9);
  if (!(steps >= 1.0 && steps <= kMaxSteps)) {
    std::ostringstream message;
    message << "with the time step " << dt << " s the run would take " << c.end_time / dt
            << " steps: it must take 1 ... " << kMaxSteps;
    throw CaseError("analysis.end.time", message.str());
  }
  return static_cast<long>(steps);
}

void prepare_materials(MpmProblem& problem, MPI_Comm comm, const std::string& work_dir,
                       const TestHooks& hooks) {
  problem.materials.prepare(problem.spec.material_ids, comm, work_dir, hooks);
}

namespace {

int rank_of(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

//! Whether this run writes checkpoints (and honours stop signals with one).
bool writes_checkpoints(const RunOptions& options) {
  return options.checkpoints && !options.run_dir.empty();
}

//! Where the main stage starts: from the run folder's last checkpoint (returning what the
//! recorder saved there), or after the gravity stage of a new run (an earlier run's
//! checkpoints in the folder removed first).
template <int D>
RecorderState start_main_stage(Solver<D>& solver, const MpmCase& c, const RunOptions& options) {
  if (options.resume) {
    remove_stale_checkpoints(options.run_dir, options.comm);
    return read_checkpoint<D>(c, solver, options.run_dir, options.comm);
  }
  if (writes_checkpoints(options))
    start_fresh_checkpoints(options.run_dir, options.comm);
  if (c.gravity_stage_steps > 0)
    run_gravity_stage(solver, c, options.comm);
  return {};
}

//! Why no checkpoint can be written (empty: they can); a case asking for periodic
//! checkpoints that cannot be written fails here, before the main stage.
template <int D>
std::string checkpoint_obstacle_of(const Solver<D>& solver, const MpmCase& c,
                                   const RunOptions& options) {
  std::string obstacle = checkpoint_obstacle(solver);
  if (writes_checkpoints(options) && c.checkpoint_every > 0 && !obstacle.empty())
    throw std::runtime_error("output.checkpoint_every: " + obstacle);
  return obstacle;
}

//! The files a main stage writes step by step: the recorder's results and the RVE snapshots.
template <int D>
struct StageOutputs {
  std::unique_ptr<Recorder<D>> recorder;
  std::unique_ptr<RveSnapshots<D>> snapshots;

  StageOutputs(const MpmCase& c, Solver<D>& solver, const RunOptions& options, long total,
               const RecorderState& resumed) {
    if (options.write_results && !options.run_dir.empty())
      recorder = std::make_unique<Recorder<D>>(c, solver, options.run_dir, total,
                                               options.resume ? &resumed : nullptr);
    if (writes_checkpoints(options) && !c.rve_snapshots.at.empty()) {
      snapshots =
          std::make_unique<RveSnapshots<D>>(c.rve_snapshots, solver, options.run_dir, total);
      if (!options.resume)
        snapshots->after_step(solver);
    }
  }

  void after_step(Solver<D>& solver) {
    if (recorder)
      recorder->after_step(solver);
    if (snapshots)
      snapshots->after_step(solver);
  }
};

//! A checkpoint or a stop waiting for a step where the materials can be resumed exactly
//! (Material::at_exact_checkpoint).
struct DeferredCheckpoint {
  bool due = false;
  bool stop_announced = false;
};

//! After a main-stage step of a run with checkpoints: writes one when due or when a stop
//! signal arrived (and the materials allow it); true when the run must stop now. A stop after
//! the last step is not honoured: the run is complete, nothing to resume. Where the materials
//! cannot be resumed exactly after this step, both wait for the first step where they can.
template <int D>
bool checkpoint_or_stop(const MpmCase& c, Solver<D>& solver, const Recorder<D>* recorder,
                        const RunOptions& options, long total, const std::string& obstacle,
                        DeferredCheckpoint& deferred) {
  const int rank = rank_of(options.comm);
  const bool stop = stop_requested(options.comm) && solver.steps() < total;
  const bool due =
      (deferred.due || (c.checkpoint_every > 0 && solver.steps() % c.checkpoint_every == 0)) &&
      solver.steps() < total;
  if ((stop || due) && obstacle.empty() && !at_exact_checkpoint(solver)) {
    deferred.due = due;
    if (stop && !deferred.stop_announced && rank == 0) {
      std::printf(
          "stop signal after step %ld: stepping on to where the RVEs set up, to write "
          "an exact checkpoint\n",
          solver.steps());
      std::fflush(stdout);
    }
    deferred.stop_announced = deferred.stop_announced || stop;
    return false;
  }
  deferred.due = false;
  if ((stop || due) && obstacle.empty()) {
    const double t0 = MPI_Wtime();
    write_checkpoint<D>(c, solver, recorder ? recorder->state() : RecorderState{}, options.run_dir,
                        options.comm);
    if (rank == 0) {
      std::printf("checkpoint at step %ld written in %.3f s\n", solver.steps(), MPI_Wtime() - t0);
      std::fflush(stdout);
    }
  }
  if (stop && rank == 0) {
    if (obstacle.empty())
      std::printf("stopped by a signal after step %ld: continue with --resume %s\n", solver.steps(),
                  options.run_dir.c_str());
    else
      std::printf("stopped by a signal after step %ld, no checkpoint: %s\n", solver.steps(),
                  obstacle.c_str());
    std::fflush(stdout);
  }
  return stop;
}

//! Collective: the run's summary (the materials' statistics gathered over the ranks).
template <int D>
void finish_run(const Solver<D>& solver, Recorder<D>* recorder, const MpmCase& c,
                const RunOptions& options, std::chrono::steady_clock::time_point start) {
  materials::Statistics statistics = solver.materials().statistics();
  statistics.gather(options.comm);
  if (!recorder)
    return;
  RunTotals totals;
  totals.statistics = std::move(statistics);
  totals.gravity_stage_steps = c.gravity_stage_steps;
  totals.ranks = options.ranks;
  totals.wall_seconds =
      options.prior_seconds +
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  recorder->finish(solver, totals);
}

}  // namespace

template <int D>
bool run_case(MpmProblem problem, const RunOptions& options,
              const std::function<void(const Solver<D>&)>& observer) {
  const auto start = std::chrono::steady_clock::now();
  const MpmCase& c = problem.spec;
  Solver<D> solver(c, std::move(problem.materials));
  const RecorderState resumed = start_main_stage(solver, c, options);
  const std::string obstacle = checkpoint_obstacle_of(solver, c, options);
  const long total = main_stage_steps(c, solver.dt());
  StageOutputs<D> outputs(c, solver, options, total, resumed);
  const int rank = rank_of(options.comm);
  DeferredCheckpoint deferred;
  while (solver.steps() < total) {
    solver.step();
    outputs.after_step(solver);
    if (observer)
      observer(solver);
    if (!writes_checkpoints(options))
      continue;
    options.hooks.at(TestHooks::Moment::step_recorded, solver.steps(), rank);
    if (checkpoint_or_stop(c, solver, outputs.recorder.get(), options, total, obstacle, deferred))
      return false;
    options.hooks.at(TestHooks::Moment::step_finished, solver.steps(), rank);
  }
  finish_run(solver, outputs.recorder.get(), c, options, start);
  return true;
}

template bool run_case<2>(MpmProblem, const RunOptions&,
                          const std::function<void(const Solver<2>&)>&);
template bool run_case<3>(MpmProblem, const RunOptions&,
                          const std::function<void(const Solver<3>&)>&);

}  // namespace mpm_lig::mpm
