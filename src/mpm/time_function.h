#pragma once

#include <string>

#include "core/case_node.h"

namespace mpm_lig::mpm {

//! A dimensionless multiplier of time for prescribed velocities and tractions.
//!
//! constant: 1; ramp: t / time up to 1, then 1; triangular: a triangle wave of period T
//! starting at 0 and rising (peak 1 at T/4, -1 at 3T/4); square: +1 in the first and last
//! quarter of each period, -1 in between (a velocity that gives a triangular displacement
//! about 0, as cyclic simple shear wants); sine: sin(2 pi t / T). A time within round-off of a
//! quarter period counts as that quarter, so a step dividing T/4 switches a square wave on time.
struct TimeFunction {
  enum class Kind { constant, ramp, triangular, square, sine };
  Kind kind = Kind::constant;
  double time = 1.0;  //!< ramp time or period [s]

  double at(double t) const;
  //! Read from `node.key` (absent: constant).
  static TimeFunction read(const CaseNode& node, const std::string& key);
};

}  // namespace mpm_lig::mpm
