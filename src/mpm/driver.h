#pragma once

#include <functional>
#include <string>

#include "mpm/case_spec.h"
#include "mpm/solver.h"

namespace mpm_lig::mpm {

//! Runs a validated case: the gravity stage (if any), then the main stage until the end
//! time or step count, with the Recorder's output when `directory` is not empty.
//! `observer` (optional) sees the solver after every main-stage step: tests use it.
template <int D>
void run_case(MpmCase& c, const std::string& directory,
              const std::function<void(const Solver<D>&)>& observer = {});

//! Steps the main stage will take.
long main_stage_steps(const MpmCase& c, double dt);

}  // namespace mpm_lig::mpm
