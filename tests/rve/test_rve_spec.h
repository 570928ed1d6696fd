#pragma once

#include <nlohmann/json.hpp>

#include "core/case_node.h"
#include "rve/spec.h"

namespace mpm_lig::test {

//! The packing the RVE tests share: 100 discs of radius 3-7 mm, glass-like Hertz contacts,
//! prepared at 100 kPa, 50 fixed substeps per increment. Each test changes only the keys it is
//! about (engine, dimension, grains, seed, preparation).
inline nlohmann::json small_rve_json() {
  return {{"dimension", 2},
          {"grains", 100},
          {"radius", {{"min", 0.003}, {"max", 0.007}}},
          {"density", 2650},
          {"seed", 3},
          {"contact",
           {{"youngs_modulus", 7e8},
            {"poisson_ratio", 0.3},
            {"friction", 0.5},
            {"damping_ratio", 0.1}}},
          {"time_step_fraction", 0.15},
          {"preparation", {{"confining_pressure", 1e5}}},
          {"substeps", {{"fixed", 50}}}};
}

//! `rve` read as the case reader reads a case's "rve" node.
inline rve::RveSpec parse_rve(const nlohmann::json& rve) {
  const auto doc = CaseDocument::parse(nlohmann::json{{"rve", rve}}.dump());
  return rve::parse_rve_spec(doc.root().child("rve"));
}

}  // namespace mpm_lig::test
