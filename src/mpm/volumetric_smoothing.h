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
  //! With tr L̃_p = Σ_{q in p's cell} V_q tr L_q / V_cell: S̃_q = S_q − (tr S_q / D) I +
  //! (V_q / V_cell) Σ_{p in q's cell} (tr S_p / D) I. The cells are those of the positions the
  //! context holds: a point that crosses a cell face within the step is counted in the cell
  //! it starts from here and in the one it ends in by apply().
  void pull_back(const KinematicsContext<D>& context,
                 std::vector<typename KinematicsOperator<D>::Tensor>& tensors) const override;
};

}  // namespace mpm_lig::mpm
