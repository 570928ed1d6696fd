#pragma once

#include "core/analysis.h"

namespace mpm_lig::mpm {

//! Adds the MPM analyses ("mpm") to `registry`.
void register_analyses(AnalysisRegistry& registry);

}  // namespace mpm_lig::mpm
