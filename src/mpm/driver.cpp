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

template <int D>
void run_case(MpmCase& c, const std::string& directory,
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
  if (!directory.empty())
    recorder = std::make_unique<Recorder<D>>(c, solver, directory, total);
  while (solver.steps() < total) {
    solver.step();
    if (recorder)
      recorder->after_step(solver);
    if (observer)
      observer(solver);
  }
  if (recorder) {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    recorder->finish(solver, c.gravity_stage_steps, wall);
  }
}

template void run_case<2>(MpmCase&, const std::string&,
                          const std::function<void(const Solver<2>&)>&);
template void run_case<3>(MpmCase&, const std::string&,
                          const std::function<void(const Solver<3>&)>&);

}  // namespace mpm_lig::mpm
