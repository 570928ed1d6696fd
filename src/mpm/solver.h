#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "mpm/case_spec.h"
#include "mpm/constraints.h"
#include "mpm/footing.h"
#include "mpm/grid.h"
#include "mpm/kinematics.h"
#include "mpm/particles.h"
#include "mpm/second_gradient.h"
#include "mpm/shape_function.h"

namespace mpm_lig::mpm {

//! Explicit MPM in D = 2 (plane strain) or 3 dimensions.
//!
//! One step (MUSL; USL skips the remap):
//!   compute_shape_functions → map_particles_to_grid (mass, momentum, forces) →
//!   update_grid (damping, acceleration, constraints, footing) → map_grid_to_particles
//!   (PIC/FLIP velocity, position) → remap_momentum (MUSL: nodal velocity from the updated
//!   point momenta, constraints again) → compute_deformation (L, dF) → apply_kinematics (the
//!   case's operators on dF, kinematics.h) → accumulate_deformation (F, volume) →
//!   update_stress (one batch call per material). Diagram: docs/DESIGN.md §6.
template <int D>
class Solver {
 public:
  using Vec = Eigen::Matrix<double, D, 1>;

  //! A solver for case `c` that owns `materials`, which must be prepared
  //! (MaterialSet::prepare): their points are added here.
  Solver(const MpmCase& c, MaterialSet materials);

  //! Advance one step of size dt().
  void step();

  //! Quasi-static gravity stage: prescribed velocities and footings frozen, `damping`
  //! instead of the case's; call begin_main_stage() after it.
  void set_gravity_stage(bool on, double damping);
  //! Start the main stage: time 0, velocities 0, displacements measured from here.
  void begin_main_stage();

  double time() const { return time_; }
  double dt() const { return dt_; }
  //! The step over the cell and the fastest wave of the materials as they are now: the CFL
  //! number the step has become where a material stiffens (packings under a footing).
  double stiffened_cfl() const;
  long steps() const { return steps_; }
  const Particles<D>& particles() const { return particles_; }
  const Grid<D>& grid() const { return grid_; }
  const std::vector<RigidFooting<D>>& footings() const { return footings_; }
  const NodeConstraints<D>& constraints() const { return constraints_; }
  //! Each point's deformation increment dF of the last step (what its material received).
  const std::vector<Mat3>& increments() const { return increments_; }
  //! The materials, const through a const solver: their collective and mutating calls
  //! (checkpoints, snapshots) need the mutable one.
  const MaterialSet& materials() const { return materials_; }
  MaterialSet& materials() { return materials_; }

  //! For a resumed run: the state a checkpoint overwrites (then restore_clock).
  Particles<D>& mutable_particles() { return particles_; }
  std::vector<RigidFooting<D>>& mutable_footings() { return footings_; }
  void restore_clock(double time, long steps) {
    time_ = time;
    steps_ = steps;
  }

  double kinetic_energy() const;
  //! The internal length's second-gradient energy (0 without one): what the footing's work
  //! stores in the gradient rather than spends in the materials.
  double gradient_energy() const;
  //! What the bounded second gradient's relaxations dissipated so far (0 unbounded).
  double gradient_dissipation() const;
  //! The work the local damping forces have taken out of the motion since the main stage
  //! began [J; per unit thickness in 2D], with output.damping_work (else 0): a quasi-static
  //! answer should not depend on it, and a footing in steady flow pays it on every moving
  //! node (docs/methods.md §7).
  double damping_work() const { return damping_work_; }
  void restore_damping_work(double work) { damping_work_ = work; }
  bool records_damping_work() const { return record_damping_work_; }
  bool has_second_gradient() const { return second_gradient_ != nullptr; }
  //! The second gradient, for its checkpoint (null without one).
  SecondGradient<D>* mutable_second_gradient() { return second_gradient_.get(); }
  const SecondGradient<D>* second_gradient() const { return second_gradient_.get(); }
  double total_mass() const;
  Vec total_momentum() const;

 private:
  //! The cell over the fastest wave speed, times `cfl`.
  double stable_time_step(double cfl) const;
  //! Largest wave speed of the materials: of their moduli as set at the start, or `now`, as
  //! their points' state has stiffened them.
  double wave_speed(bool now) const;
  //! A fixed time step above the stable step (CFL 1) is refused, unless every node's
  //! velocity is prescribed: the explicit update would grow without bound, or, damped, end
  //! with a wrong answer and no error.
  void check_fixed_time_step(const MpmCase& c) const;
  void compute_shape_functions();
  //! The second-gradient energy's share of each point's internal-force tensor
  //! (analysis.internal_length, method second_gradient): gradient_forces_.
  void compute_gradient_forces();
  //! Bring a position that left through a periodic face back in through the other.
  void wrap_periodic(Vec& x) const;
  void compute_external_forces();
  void map_particles_to_grid();
  void update_grid();
  //! The step's share of damping_work_: v* after the constraints against trial_velocity_.
  void add_damping_work();
  void apply_boundary_conditions(bool record);
  void map_grid_to_particles();
  void remap_momentum();
  //! Each point's velocity gradient L and increment dF into increments_.
  void compute_deformation();
  //! The kinematics phase: the case's operators rewrite increments_, in order.
  void apply_kinematics();
  //! F ← dF F and V ← det(dF) V with the increments the materials get.
  void accumulate_deformation();
  void update_stress();

  MaterialSet materials_;  // first: the particles are added to it
  Grid<D> grid_;
  Particles<D> particles_;
  std::unique_ptr<ShapeFunction1d> shape_;
  NodeConstraints<D> constraints_;
  std::vector<RigidFooting<D>> footings_;
  std::vector<std::unique_ptr<KinematicsOperator<D>>> kinematics_;
  std::unique_ptr<SecondGradient<D>> second_gradient_;  // null: no second-gradient energy
  std::vector<Traction> tractions_;
  std::vector<std::vector<std::size_t>> traction_points_;
  Vec gravity_;

  bool musl_;
  double flip_;
  double damping_;
  double case_damping_;
  bool record_damping_work_;
  double damping_work_ = 0.0;
  std::vector<Vec> trial_velocity_;  // v* before the constraints, with record_damping_work_
  double mass_scaling_;
  //! The stiffest material's wave modulus [Pa]: the scale of a penalty footing's stiffness.
  double contact_modulus_ = 0.0;
  double prescribed_scale_ = 1.0;  // 0 in the gravity stage

  double dt_ = 0.0;
  double gradient_modulus_ = 0.0;  // the second gradient's stiffening of the shortest waves
  double time_ = 0.0;
  long steps_ = 0;

  // Per-step work arrays.
  std::vector<PointWeights<D>> weights_;
  std::vector<Mat3> increments_;
  std::vector<Eigen::Matrix<double, D, D>> gradient_forces_;
  // Per material: the points (solver indices) and the batch handed to update().
  std::vector<std::vector<std::size_t>> batch_particles_;
  std::vector<std::vector<std::size_t>> batch_points_;
  std::vector<std::vector<Mat3>> batch_increments_;
  std::vector<std::vector<Mat3>> batch_stress_;
};

}  // namespace mpm_lig::mpm
