#pragma once

#include "core/tensor.h"

namespace mpm_lig::materials {

//! A deformation increment split into a strain increment and a rotation, both referred to
//! the end of the step.
struct StrainIncrement {
  Mat3 strain;    //!< symmetric strain increment Δε
  Mat3 rotation;  //!< orthogonal rotation ΔR (det +1)
};

//! Hughes–Winget (1980) split of a deformation increment `dF` (F_new = dF F_old).
//!
//! With the midpoint gradient G = 2 (dF − I)(dF + I)^-1, Δε = sym G and the rotation is
//! the Cayley transform ΔR = (I − ½ skew G)^-1 (I + ½ skew G): exactly orthogonal, so
//! σ_new = ΔR σ ΔR^T + Δσ is the Jaumann rate integrated in an incrementally objective way.
//! A rigid rotation dF = Q (below 180° per step) gives Δε = 0 and ΔR = Q exactly.
//! Throws std::runtime_error when det dF <= 0 or dF + I is singular (a step that inverts
//! the material point).
StrainIncrement split_increment(const Mat3& dF);

//! Rotate a symmetric tensor: R t R^T.
inline Mat3 rotated(const Mat3& t, const Mat3& r) {
  return r * t * r.transpose();
}

}  // namespace mpm_lig::materials
