#pragma once

#include "core/case_node.h"
#include "core/tensor.h"

namespace mpm_lig::materials {

//! Isotropic linear elasticity, from Young's modulus and Poisson's ratio.
struct Elasticity {
  double youngs_modulus = 0.0;  //!< E [Pa]
  double poisson_ratio = 0.0;   //!< ν [-]
  double bulk = 0.0;            //!< K = E / (3 (1 − 2ν)) [Pa]
  double shear = 0.0;           //!< G = E / (2 (1 + ν)) [Pa]
  double lame = 0.0;            //!< λ = K − 2G/3 [Pa]

  static Elasticity from_moduli(double youngs_modulus, double poisson_ratio);
  //! Reads `youngs_modulus` (> 0) and `poisson_ratio` (in (−1, 0.5)) of a material node.
  static Elasticity read(const CaseNode& node);

  //! Constrained (P-wave) modulus λ + 2G.
  double wave_modulus() const { return lame + 2.0 * shear; }
  //! Δσ = λ tr(Δε) I + 2G Δε.
  Mat3 stress(const Mat3& strain) const {
    return lame * strain.trace() * Mat3::Identity() + 2.0 * shear * strain;
  }
};

//! Required number strictly between `lo` and `hi` (open bounds: where a law degenerates).
double read_open_range(const CaseNode& node, const std::string& key, double lo, double hi);

}  // namespace mpm_lig::materials
