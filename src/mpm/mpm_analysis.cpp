#include "mpm/mpm_analysis.h"

#include <mpi.h>

#include <cstdio>

#include "mpm/case_size.h"
#include "mpm/case_spec.h"
#include "mpm/driver.h"
#include "mpm/resume_check.h"

namespace mpm_lig::mpm {
namespace {

//! The local damping opposes every moving node's velocity with a share of its unbalanced force:
//! under a footing driven at a speed the soil flows steadily one way, and the damping turns the
//! force's fluctuations into a resistance that the footing's load carries (docs/methods.md §7,
//! the local damping). Said once per invocation (a resume too), on rank 0, before the
//! materials are prepared.
void warn_damped_footing(const MpmCase& c, int rank) {
  if (rank != 0 || c.damping <= 0.0)
    return;
  for (std::size_t f = 0; f < c.footings.size(); ++f) {
    if (c.footings[f].velocity == 0.0)
      continue;
    std::fprintf(stderr,
                 "mpm_lig: warning: analysis.damping %g with rigid_bodies[%zu] driven at a "
                 "speed: the local damping resists the soil's steady flow and raises the "
                 "footing's load (docs/methods.md §7, the local damping; the shipped footings "
                 "keep it so that their published results stand); analysis.damping 0 leaves "
                 "it out, output.damping_work measures it\n",
                 c.damping, f);
    return;
  }
}

//! An explicit MPM run. The MPM is replicated on every rank (same arithmetic everywhere, so
//! the same answer); a DEM material spreads its RVEs over the ranks and gathers their
//! stresses. Only rank 0 writes files and progress.
class MpmAnalysis final : public Analysis {
 public:
  explicit MpmAnalysis(MpmProblem problem) : problem_(std::move(problem)) {}

  bool supports_resume() const override { return true; }

  void check_run(const RunContext& context) const override {
    const MpmCase& c = problem_.spec;
    check_step_counts(c);
    int ranks = 1;
    MPI_Comm_size(context.comm, &ranks);
    const std::vector<double> points = points_per_material(c);
    MemoryBudget budget;
    add_mpm_memory(c, points, budget);
    for (std::size_t m = 0; m < problem_.materials.size(); ++m)
      problem_.materials[m]->check_run(static_cast<std::size_t>(points[m]), ranks,
                                       context.output_dir, budget);
    budget.check(context.comm);
    // Before anything is written or prepared (and with --validate): a resume that could lose
    // results is refused.
    if (context.resume)
      check_resume(c, context.output_dir, context.comm);
  }

  std::vector<std::string> unchecked() const override {
    std::vector<std::string> lines;
    if (!problem_.spec.fixed_time_step && problem_.spec.end_steps == 0)
      lines.push_back(
          "analysis.end.time: the step count (1 ... 1e12), which needs the CFL time "
          "step of the prepared materials");
    if (problem_.spec.fixed_time_step)
      lines.push_back(
          "analysis.time_step.fixed: against the stable time step (CFL 1), which needs the "
          "prepared materials' wave moduli");
    for (std::size_t m = 0; m < problem_.materials.size(); ++m) {
      if (materials::has_snapshots(*problem_.materials[m]))
        lines.push_back("materials[" + std::to_string(m) +
                        "]: the DEM packings (preparation or restart file contents)");
    }
    return lines;
  }

  RunEnd run(const RunContext& context) override {
    int rank = 0;
    MPI_Comm_rank(context.comm, &rank);
    const std::string& dir = context.output_dir;
    RunOptions options;
    options.run_dir = dir;
    options.write_results = rank == 0;
    options.checkpoints = true;
    options.resume = context.resume;
    options.comm = context.comm;
    MPI_Comm_size(context.comm, &options.ranks);
    const double start = MPI_Wtime();
    options.hooks = context.hooks;
    warn_damped_footing(problem_.spec, rank);
    prepare_materials(problem_, context.comm, dir + "/packings", context.hooks);
    options.prior_seconds = MPI_Wtime() - start;
    // run() is called once: the problem's materials move into the solver.
    const bool completed = problem_.spec.dimension == 2 ? run_case<2>(std::move(problem_), options)
                                                        : run_case<3>(std::move(problem_), options);
    MPI_Barrier(context.comm);
    return completed ? RunEnd::completed : RunEnd::stopped;
  }

 private:
  MpmProblem problem_;
};

}  // namespace

std::unique_ptr<Analysis> make_analysis(const CaseNode& root,
                                        const materials::MaterialRegistry& materials) {
  return std::make_unique<MpmAnalysis>(read_case(root, materials));
}

}  // namespace mpm_lig::mpm
