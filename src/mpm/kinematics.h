#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/tensor.h"
#include "mpm/case_spec.h"
#include "mpm/grid.h"
#include "mpm/particles.h"

namespace mpm_lig::mpm {

//! What a kinematics operator sees of the step (docs/DESIGN.md §6, the kinematics phase).
//!
//! Every rank holds every point (the MPM is replicated; only a dem_rve material spreads its
//! RVEs over the ranks), so an operator sees all points on every rank and needs no messages.
template <int D>
struct KinematicsContext {
  //! For apply(): positions at the end of the step (after grid → points); volumes still those
  //! of its start (the increments are applied to F and V after the operators); masses,
  //! materials. For pull_back(): the step's start (the forces are computed before the motion).
  const Particles<D>& particles;
  const Grid<D>& grid;  //!< cells, for a neighbourhood or a cell average
  double dt;            //!< the step [s]
};

//! An operator on the points' deformation increments between the deformation and the stress
//! update: it rewrites ΔF (F_new = ΔF F_old, spin included), which F, V and the materials then
//! receive; no material knows it ran.
//!
//! An operator must give the same increments on every rank and after a resume: it reads only
//! what the context holds, sums in point order, and keeps no state from step to step (apply()
//! is const; an operator with memory would need a checkpoint hook, which this interface does
//! not have).
template <int D>
class KinematicsOperator {
 public:
  virtual ~KinematicsOperator() = default;
  //! The case key that chose it ("volumetric_smoothing", "internal_length").
  virtual std::string name() const = 0;
  //! Rewrite `increments` (one per point of context.particles, in point order).
  virtual void apply(const KinematicsContext<D>& context, std::vector<Mat3>& increments) const = 0;

  using Tensor = Eigen::Matrix<double, D, D>;
  //! The work-conjugate of apply() for force tensors (each point's S, with S_p : L_p its share
  //! of the power): rewrite `tensors` into S̃ with Σ_p S̃_p : L_p = Σ_p S_p : L̃_p, L̃ the
  //! velocity gradients as apply() rewrites them (to first order in the step). An energy's
  //! forces (the second gradient's) go through it, so that they do the work the energy's own
  //! change accounts for. An operator that cannot run beside such an energy keeps this
  //! default, which refuses.
  virtual void pull_back(const KinematicsContext<D>& context, std::vector<Tensor>& tensors) const;
};

//! The operators case `c` asks for, in the order they apply: `analysis.internal_length`
//! (NonlocalDeformation), `analysis.volumetric_smoothing` (VolumetricSmoothing). None when it asks
//! for none: the increments go to the materials as computed.
template <int D>
std::vector<std::unique_ptr<KinematicsOperator<D>>> kinematics_operators(const MpmCase& c);

}  // namespace mpm_lig::mpm
