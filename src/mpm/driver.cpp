#include "mpm/driver.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "mpm/recorder.h"

namespace mpm_lig::mpm {

long main_stage_steps(const MpmCase& c, double dt) {
  if (c.end_steps > 0)
    return c.end_steps;
  // The last step may overshoot the end time by less than one step.
  return static_cast<long>(std::ceil(c.end_time / dt - 1e-9));
}

void prepare_materials(MpmCase& c, MPI_Comm comm, const std::string& work_dir) {
  materials::MaterialContext context;
  context.comm = comm;
  for (std::size_t m = 0; m < c.materials.size(); ++m) {
    context.work_dir = work_dir + "/m" + std::to_string(c.material_ids[m]);
    c.materials[m]->prepare(context);
  }
}

template <int D>
void run_case(MpmCase& c, const RunOptions& options,
              const std::function<void(const Solver<D>&)>& observer) {
  const auto start = std::chrono::steady_clock::now();
  Solver<D> solver(c);
  if (c.gravity_stage_steps > 0) {
    solver.set_gravity_stage(true, c.gravity_stage_damping);
    for (long k = 0; k < c.gravity_stage_steps; ++k)
      solver.step();
    solver.begin_main_stage();
  }
  const long total = main_stage_steps(c, solver.dt());
  std::unique_ptr<Recorder<D>> recorder;
  if (!options.directory.empty())
    recorder = std::make_unique<Recorder<D>>(c, solver, options.directory, total);
  while (solver.steps() < total) {
    solver.step();
    if (recorder)
      recorder->after_step(solver);
    if (observer)
      observer(solver);
  }
  if (recorder) {
    RunTotals totals;
    totals.gravity_stage_steps = c.gravity_stage_steps;
    totals.ranks = options.ranks;
    totals.wall_seconds =
        options.prior_seconds +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    recorder->finish(solver, totals);
  }
}

template void run_case<2>(MpmCase&, const RunOptions&,
                          const std::function<void(const Solver<2>&)>&);
template void run_case<3>(MpmCase&, const RunOptions&,
                          const std::function<void(const Solver<3>&)>&);

}  // namespace mpm_lig::mpm
