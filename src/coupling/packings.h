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

//! Which of K packings each point is cloned from (the material's `packing_order`): cyclic,
//! point i ← packing i mod K; scattered, point i ← packing h(i) mod K, h a fixed integer hash
//! (the same on every machine and rank count). The points are numbered along x first, so
//! cyclic with an even number of points a row clones alternate columns from alternate
//! packings: an imperfection at the shortest wave, where the internal length's fitted
//! gradient is blind (docs/methods.md §7, the odd-even mode).
struct PackingOrder {
  std::size_t count = 1;
  bool scattered = false;
  std::size_t of(std::size_t point) const;
};

//! Collective over `context.comm`: the `count` packings of a dem_rve material (its case path
//! `path`), spread over rank groups of `ranks_per_rve` like RVEs are. Each is generated with
//! seed spec.seed + k, consolidated and saved as `context.work_dir`/packing_<k>.restart, or
//! loaded from spec.restart_file; then probed for its moduli (a 1e-4 uniaxial strain). Every
//! rank gets every packing. Throws StopRequested on every rank when a stop was asked for.
std::vector<Packing> prepare_packings(const rve::RveSpec& spec, int count, int ranks_per_rve,
                                      const std::string& path,
                                      const materials::MaterialContext& context);

}  // namespace mpm_lig::coupling
