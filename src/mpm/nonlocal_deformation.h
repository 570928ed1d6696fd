#pragma once

#include "mpm/kinematics.h"

namespace mpm_lig::mpm {

//! Non-local deformation increment (`analysis.internal_length`, docs/methods.md §7): each
//! point's stretch increment is replaced by a Gaussian-weighted mean over the points within
//! reach of the length ℓ (of every material: the motion is one field across a material's
//! edge), so that a softening material cannot concentrate its strain into a band narrower
//! than ℓ whatever the mesh.
//!
//! ΔF = V R (left polar decomposition). The operator averages log V, weighted by the kernel
//! times the point's volume, and keeps each point's own rotation R:
//!   log V̂_p = (1 − m) log V_p + m Σ_q w_pq V_q log V_q / Σ_q w_pq V_q,   ΔF̂_p = exp(log V̂_p) R_p,
//! with w_pq = exp(−r²/2s²), s = ℓ / (2 √(2 ln 2)) (ℓ is the kernel's full width at half
//! height), cut at 3s; r is the nearest-image distance along periodic axes. m = 1 is the plain
//! non-local average, m < 1 keeps a local part, m > 1 is over-non-local. A rigid motion has
//! V = I at every point, so it passes unchanged: no stress from a rotation, however fast.
template <int D>
class NonlocalDeformation final : public KinematicsOperator<D> {
 public:
  NonlocalDeformation(double length, double nonlocal_weight);
  std::string name() const override { return "internal_length"; }
  void apply(const KinematicsContext<D>& context, std::vector<Mat3>& increments) const override;

  //! The kernel's standard deviation s for a length ℓ.
  static double kernel_width(double length);

 private:
  double sigma_;   // s [m]
  double cutoff_;  // 3 s [m]
  double weight_;  // m
};

}  // namespace mpm_lig::mpm
