#pragma once

#include "mpm/kinematics.h"

namespace mpm_lig::mpm {

//! Cell-averaged volume change, an F-bar for MPM (`analysis.volumetric_smoothing`): the
//! in-plane part of each ΔF is rescaled so that its determinant is the volume-weighted mean of
//! the determinants of the points in its cell. Removes the volumetric locking of isochoric
//! plastic flow on low-order shape functions (docs/methods.md §1).
template <int D>
class VolumetricSmoothing final : public KinematicsOperator<D> {
 public:
  std::string name() const override { return "volumetric_smoothing"; }
  void apply(const KinematicsContext<D>& context, std::vector<Mat3>& increments) const override;
};

}  // namespace mpm_lig::mpm
