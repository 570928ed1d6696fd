#pragma once

#include <memory>
#include <optional>

#include "core/tensor.h"
#include "element/element_spec.h"

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
  //! After an increment (or a previous correction): a further deformation, within the same
  //! increment, that brings the stress-controlled directions back to their target; none when
  //! the stress is on target (or the path controls no stress).
  virtual std::optional<Mat3> correction(const Mat3& /*stress*/) { return std::nullopt; }
  //! DEM steps of increment `k`; 0: the RVE's sub-stepping rule (docs/DESIGN.md §8), the one
  //! the coupling uses for an MPM point's update.
  virtual int substeps(int /*k*/) const { return 0; }
  //! The deformation gradient the path starts from (the packing is taken to be in it).
  virtual Mat3 start() const { return Mat3::Identity(); }
};

//! A servo's stiffness estimates [Pa per unit log strain], one for expanding and one for
//! contracting corrections (a packing unloading towards failure is soft, reloading stiff),
//! each re-estimated from a correction's secant response, averaged geometrically with the
//! previous estimate and kept within [1/50, 4] times the first, so that the noise of a small
//! packing cannot run it away. Shared by the drained test's lateral servo and the mean-stress
//! servo of a recorded path with a free volume.
class ServoStiffness {
 public:
  explicit ServoStiffness(double first) : first_(first), expanding_(first), contracting_(first) {}
  //! The estimate for a strain of the sign of `expand` (> 0: expanding).
  double& operator()(double expand) { return expand > 0.0 ? expanding_ : contracting_; }
  //! After a correction: `num` = Σ −Δσ'ᵢ Δεᵢ, `den` = Σ Δεᵢ² (least squares over the
  //! corrected axes), `direction` = Σ Δεᵢ; no update unless both are > 0.
  void update(double num, double den, double direction);

 private:
  double first_;
  double expanding_, contracting_;
};

//! The path of `test` for an RVE of `dimension`; `lateral_stiffness` [Pa per unit strain] is
//! the servo's first estimate of the packing's stiffness (drained tests, recorded paths with a
//! free volume). A recorded path comes from recorded_path.h.
std::unique_ptr<StrainPath> make_strain_path(const ElementTestSpec& test, int dimension,
                                             double confining_pressure, double lateral_stiffness);

}  // namespace mpm_lig::element
