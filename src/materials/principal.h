#pragma once

#include "core/tensor.h"

namespace mpm_lig::materials {

//! Principal values of a symmetric tensor, sorted σ1 ≥ σ2 ≥ σ3, with unit eigenvectors as
//! the columns of `vectors` in the same order.
struct Principal {
  Vec3 values;
  Mat3 vectors;
};

//! Spectral decomposition of a symmetric tensor. Plane states (xz = yz = 0 exactly, as
//! in plane strain) take a closed-form 2x2 path: fast and exact in the out-of-plane axis.
Principal principal(const Mat3& t);

//! Principal values only, sorted σ1 ≥ σ2 ≥ σ3: cheaper, for yield checks.
Vec3 principal_values(const Mat3& t);

//! t + Q diag(change) Q^T: apply a change of principal values while keeping the axes. Adding
//! the change (rather than rebuilding t) keeps untouched components bit-exact.
Mat3 with_principal_change(const Mat3& t, const Principal& p, const Vec3& change);

}  // namespace mpm_lig::materials
