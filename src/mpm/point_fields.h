#pragma once

#include "core/tensor.h"

namespace mpm_lig::mpm {

//! Logarithmic (Hencky) strain ln(V) = 1/2 ln(F F^T), compression negative.
Mat3 hencky_strain(const Mat3& deformation);

//! Deviatoric strain invariant eps_q = sqrt(2/3 e:e), e the deviatoric part of `strain`.
double deviatoric_strain(const Mat3& strain);

}  // namespace mpm_lig::mpm
