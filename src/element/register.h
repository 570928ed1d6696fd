#pragma once

#include "core/analysis.h"

namespace mpm_lig::element {

//! Adds the element-test analyses ("element_test") to `registry`.
void register_analyses(AnalysisRegistry& registry);

}  // namespace mpm_lig::element
