#pragma once

#include "core/analysis.h"
#include "materials/material.h"

namespace mpm_lig::mpm {

//! Adds the MPM analyses ("mpm") to `registry`; their materials come from `materials`
//! (assembled by the program: the continuum laws and, with a DEM engine, "dem_rve").
void register_analyses(AnalysisRegistry& registry, materials::MaterialRegistry materials);

}  // namespace mpm_lig::mpm
