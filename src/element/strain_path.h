#pragma once

#include <memory>

#include "core/tensor.h"
#include "element/element_test.h"

namespace mpm_lig::element {

//! A strain path: the deformation increment of each step, from the current stress (for the
//! stress-controlled directions of drained tests).
class StrainPath {
 public:
  virtual ~StrainPath() = default;
  //! Total number of increments.
  virtual int increments() const = 0;
  //! Increment `k` (0-based) given the current Cauchy stress (tension positive).
  virtual Mat3 increment(int k, const Mat3& stress) = 0;
};

//! The path of `test` for an RVE of `dimension`; `lateral_stiffness` [Pa per unit strain]
//! bounds the servo gain of the stress-controlled directions (drained tests).
std::unique_ptr<StrainPath> make_strain_path(const ElementTestSpec& test, int dimension,
                                             double confining_pressure, double lateral_stiffness);

}  // namespace mpm_lig::element
