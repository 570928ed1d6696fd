#pragma once

#include <memory>
#include <string>

#include "core/analysis.h"
#include "element/element_spec.h"

namespace mpm_lig::element {

//! Creates the analysis from a whole case (keys "rve" and "analysis").
std::unique_ptr<Analysis> make_element_test(const CaseNode& root);

}  // namespace mpm_lig::element
