#pragma once

#include <vector>

#include "core/tensor.h"
#include "rve/spec.h"

namespace mpm_lig::rve {

//! A loose periodic packing: grain centres and radii in a cubic (square in 2D) cell [0, L)^d.
struct Packing {
  double cell_length = 0.0;
  std::vector<Vec3> centres;  //!< z = 0 in 2D
  std::vector<double> radii;
};

//! Random sequential placement without overlap in a periodic cell sized for
//! `spec.preparation.initial_solid_fraction`; reproducible from `spec.seed` (std::mt19937_64).
//! Throws std::runtime_error if the grains do not fit (solid fraction too high).
Packing generate_packing(const RveSpec& spec);

//! Solid volume of the grains (area in 2D).
double solid_measure(const std::vector<double>& radii, int dimension);

}  // namespace mpm_lig::rve
