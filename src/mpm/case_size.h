#pragma once

#include <string>
#include <vector>

#include "core/resources.h"
#include "mpm/case_spec.h"

namespace mpm_lig::mpm {

//! Material points along each axis of `body` (as generate_particles places them).
std::vector<double> points_along_axes(const MpmCase& c, const Body& body);
//! Where a body's points lie along `axis`: the middles of equal spacings filling its box (the
//! points are the grid of these coordinates over the axes).
std::vector<double> point_coordinates(const MpmCase& c, const Body& body, int axis);

//! Material points per material that the bodies of `c` will hold.
std::vector<double> points_per_material(const MpmCase& c);

//! Adds to `budget` the memory of the MPM itself (grid and material points, replicated on
//! every rank), measured per node and per point (docs/running.md §4).
void add_mpm_memory(const MpmCase& c, const std::vector<double>& points, MemoryBudget& budget);

//! A CaseError when a stage would take more than kMaxSteps steps (the main stage with a
//! fixed time step; a CFL time step is known only once the materials are prepared, and
//! main_stage_steps() checks it then).
void check_step_counts(const MpmCase& c);

}  // namespace mpm_lig::mpm
