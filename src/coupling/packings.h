#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/tensor.h"
#include "materials/material.h"
#include "rve/spec.h"

namespace mpm_lig::coupling {

//! One prepared packing that material points are cloned from.
struct Packing {
  std::string restart_file;    //!< engine restart (contact history included)
  Mat3 stress = Mat3::Zero();  //!< its homogenised stress, physical frame
  double void_ratio = 0.0;
  double wave_modulus = 0.0;     //!< measured constrained modulus [Pa]
  double lateral_modulus = 0.0;  //!< measured lateral stress change per axial strain [Pa]
};

//! The packing point `point` is cloned from, of `packings`: point i ← packing i mod K.
inline std::size_t packing_of(std::size_t point, std::size_t packings) {
  return point % packings;
}

//! Collective over `context.comm`: the `count` packings of a dem_rve material (its case path
//! `path`), spread over rank groups of `ranks_per_rve` like RVEs are. Each is generated with
//! seed spec.seed + k, consolidated and saved as `context.work_dir`/packing_<k>.restart, or
//! loaded from spec.restart_file; then probed for its moduli (a 1e-4 uniaxial strain). Every
//! rank gets every packing. Throws StopRequested on every rank when a stop was asked for.
std::vector<Packing> prepare_packings(const rve::RveSpec& spec, int count, int ranks_per_rve,
                                      const std::string& path,
                                      const materials::MaterialContext& context);

}  // namespace mpm_lig::coupling
