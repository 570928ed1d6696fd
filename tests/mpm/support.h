#pragma once

#include <cmath>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "materials/material.h"
#include "mpm/case_spec.h"

namespace mpm_lig::mpm::testing {

//! A rotation by `angle` about z (the plane's normal).
inline Mat3 plane_rotation(double angle) {
  Mat3 r = Mat3::Identity();
  r(0, 0) = r(1, 1) = std::cos(angle);
  r(0, 1) = -std::sin(angle);
  r(1, 0) = std::sin(angle);
  return r;
}

//! The materials the MPM tests use: the shipped ones (src/materials).
const materials::MaterialRegistry& material_registry();

//! Read cases/mpm/<name>.json, let `edit` change the JSON (refinement, shorter runs), and
//! validate it exactly as `mpm_lig` does (unknown keys included).
MpmProblem load_case(const std::string& name,
                     const std::function<void(nlohmann::json&)>& edit = {});

}  // namespace mpm_lig::mpm::testing
