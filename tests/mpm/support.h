#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "materials/material.h"
#include "mpm/case_spec.h"

namespace mpm_lig::mpm::testing {

//! The materials the MPM tests use: the shipped ones (src/materials).
const materials::MaterialRegistry& material_registry();

//! Read cases/mpm/<name>.json, let `edit` change the JSON (refinement, shorter runs), and
//! validate it exactly as `mpm_lig` does (unknown keys included).
MpmProblem load_case(const std::string& name,
                     const std::function<void(nlohmann::json&)>& edit = {});

}  // namespace mpm_lig::mpm::testing
