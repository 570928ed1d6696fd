#pragma once

#include "materials/material.h"

namespace mpm_lig::coupling {

//! Adds the multiscale materials ("dem_rve": a DEM packing per material point) to `registry`.
void register_materials(materials::MaterialRegistry& registry);

}  // namespace mpm_lig::coupling
