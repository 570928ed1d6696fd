#pragma once

#include <string>

#include "rve/rve.h"

namespace mpm_lig::rve {

//! Write PREFIX_grains.vtk (grains), PREFIX_contacts.vtk (force chains) and PREFIX_cell.vtk
//! (the periodic cell) in the physical frame. Collective; rank 0 of the RVE writes.
void write_snapshot(Rve& rve, const std::string& prefix, bool writer);

}  // namespace mpm_lig::rve
