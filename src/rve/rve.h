#pragma once

#include <memory>
#include <string>

#include <mpi.h>

#include "core/tensor.h"
#include "dem/engine.h"
#include "rve/observables.h"
#include "rve/spec.h"

namespace mpm_lig::rve {

//! One periodic DEM packing driven by deformation increments (docs/DESIGN.md §2.2).
//!
//! The engine's box h is upper triangular (the RVE frame); the rotation Q from the RVE frame to
//! the physical frame is kept here. A physical increment ΔF becomes ΔF' = Qᵀ ΔF Q, split as
//! ΔF'·h = Q_inc·R_new; the box is driven to R_new with `fix deform … final`, and Q ← Q·Q_inc.
//! All calls are collective over the RVE's communicator.
//! DEM steps of an update of box increment `effective_increment` (rotation taken out) at
//! mean stress `mean_stress` by an RVE that has sheared by `net_shear` so far (Rve::net_shear),
//! by the spec's sub-stepping rule (docs/DESIGN.md §8).
int substeps_for_increment(const RveSpec& spec, const Mat3& effective_increment, double mean_stress,
                           double net_shear);
//! Engineering shear strain γ = √2 |dev ε| of a small strain ε (the in-plane deviator in 2D):
//! γ of a simple shear.
double shear_of_strain(const Mat3& strain, int dimension);
//! The DEM steps an RVE of `spec` at mean stress `mean_stress`, sheared by `net_shear`, is
//! expected to run for the physical increment `dF`: exact for an RVE whose frame is the physical
//! one and whose box is rectangular, an estimate otherwise. Needs no RVE, so every rank can predict
//! every point.
int predicted_substeps(const RveSpec& spec, const Mat3& dF, double mean_stress, double net_shear);

class Rve {
 public:
  //! A fresh loose packing generated from `spec` (not yet consolidated: see consolidate()).
  static std::unique_ptr<Rve> generate(const RveSpec& spec, MPI_Comm comm,
                                       const std::string& label);
  //! A clone of a saved packing (engine restart file written by write_restart()), its cell
  //! turned to the spec's cell_angle (orient_cell()).
  static std::unique_ptr<Rve> from_restart(const RveSpec& spec, const std::string& restart_file,
                                           MPI_Comm comm, const std::string& label);
  //! A running RVE again from its checkpoint (write_checkpoint()); take its state() with
  //! restore(). It continues bit-identically to the original had it not been checkpointed.
  static std::unique_ptr<Rve> from_checkpoint(const RveSpec& spec, const std::string& file,
                                              MPI_Comm comm, const std::string& label);

  const RveSpec& spec() const { return spec_; }
  const std::string& label() const { return label_; }
  //! The engine's DEM step now: the preparation's on a generated packing until
  //! use_loading_time_step(), the RVE's own (spec().time_step) on every other.
  double time_step() const { return time_step_; }
  //! The packing is prepared: from here on it runs at the RVE's own step.
  void use_loading_time_step();
  //! The ranks this RVE runs on.
  MPI_Comm comm() const { return comm_; }
  dem::Engine& engine() { return *engine_; }

  //! How an update runs the engine (docs/DESIGN.md §3.3).
  enum class EngineRun {
    set_up,     //!< the engine's full set-up first (`run … pre yes`): every shipped update
    continued,  //!< continue the last continued run without a set-up (Engine::run_continued);
                //!< the first after require_setup(), a checkpoint or a cell change sets up
  };
  //! Apply the physical deformation increment `dF` over `substeps` DEM steps (0: as the spec's
  //! sub-stepping rule says). Returns the number of DEM steps run.
  int deform(const Mat3& dF, int substeps = 0, EngineRun run = EngineRun::set_up);
  //! The next continued update runs the engine's full set-up (the caller says when:
  //! rve.setup_every, so that a checkpoint or a move between ranks falls where every RVE sets up).
  void require_setup();
  //! Let the packing evolve without deformation (removes any streaming motion).
  void relax(int steps) { deform(Mat3::Identity(), steps); }

  //! Stress, void ratio, coordination and energies now (physical frame).
  Observables observe();
  //! observe() without the contact forces (add_health_measures): stress, void ratio and what
  //! check_blow_up reads, at a small part of the cost. What an MPM update needs.
  Observables observe_health();
  //! The stress only (cheap: no grain gathering), physical frame, tension positive.
  Mat3 stress();
  //! Throws std::runtime_error naming the RVE on a numerical blow-up: lost grains, NaN, a
  //! grain crossing kMaxStepTravel radii in one DEM step, or an overlap beyond kMaxOverlapRatio.
  void check_blow_up(const Observables& now) const;
  //! check_blow_up, and runaway kinetic energy: above max_kinetic_ratio × the elastic energy
  //! and max_flow_ratio × the flow energy (a liquefied packing passes).
  void check_health(const Observables& now) const;

  //! Turn a packing prepared in its own frame so that its cell's first side lies at the spec's
  //! cell_angle in the physical frame (a rigid turn of the whole packing: the grains and the box
  //! keep their engine coordinates; only the rotation to the physical frame changes). 0: nothing.
  void orient_cell();

  //! Change the sliding friction (compaction towards a target void ratio).
  void set_friction(double friction);
  //! Save the packing with its contact history (the rotation Q is not part of it).
  void write_restart(const std::string& file);

  //! The state beyond the engine's restart file: rotation Q, streaming gradient, counters.
  //! Checkpoints and moves between ranks keep it field by field, as the table
  //! coupling/rve_state_fields.h lists them (a new field: one line there).
  struct State {
    Mat3 rotation = Mat3::Identity();
    Mat3 streaming = Mat3::Zero();
    double particle_steps = 0.0;
    double last_mean_stress = 0.0;
    //! Σ sym(ΔF_eff − 1) over the box increments (RVE frame): the net strain the packing has
    //! run, reversals cancelled (the sub-step rule reads its shear).
    Mat3 strain = Mat3::Zero();
  };
  //! Checkpoint of a running RVE: the engine restart (contact history and streaming velocities
  //! kept) in `file` and the exact grain placement in placement_file(`file`). Writing it leaves
  //! this RVE's arithmetic untouched, and after from_checkpoint + restore(state()) a clone
  //! continues bit-identically (one rank per RVE; docs/DESIGN.md §10).
  void write_checkpoint(const std::string& file);
  //! The file beside a checkpoint's restart file that keeps the exact placement.
  static std::string placement_file(const std::string& checkpoint_file);
  State state() const {
    return {rotation_, streaming_, particle_steps_, last_mean_stress_, strain_};
  }
  //! Take the state a checkpoint saved (after from_restart of its restart file).
  void restore(const State& s);

  //! Box matrix (columns a, b, c) in the RVE frame, and the rotation to the physical frame.
  Mat3 box_matrix() const;
  const Mat3& rotation() const { return rotation_; }
  //! Cell volume (area × thickness in 2D: the volume the stress refers to).
  double volume() const;
  //! Accumulated DEM particle-steps (grains × steps) of this RVE.
  double particle_steps() const { return particle_steps_; }
  //! γ of the net strain its box increments have run so far (clones start at 0).
  double net_shear() const { return shear_of_strain(strain_, spec_.dimension); }

 private:
  Rve(const RveSpec& spec, MPI_Comm comm, const std::string& label);
  //! An RVE whose engine read `restart_file` (checked first), with the material set up.
  static std::unique_ptr<Rve> read(const RveSpec& spec, const std::string& restart_file,
                                   MPI_Comm comm, const std::string& label);
  int substeps_for(const Mat3& effective_increment);
  void reduce_cell_basis();
  void set_streaming(const Mat3& gradient);
  void run_to_box(const Mat3& target, int steps, EngineRun run);
  //! The `fix deform` line that drives the box to `target` over the next run.
  std::string deform_fix(const Mat3& target) const;
  //! Void ratio and step travel of `o` from the gathered grains.
  void add_cell_measures(const GrainState& grains, Observables& o) const;
  //! The engine's write_restart, then the file checked whole on every rank (throws if not).
  void write_checked_restart(const std::string& file);

  RveSpec spec_;
  std::string label_;
  MPI_Comm comm_;
  std::unique_ptr<dem::Engine> engine_;
  double time_step_;
  Mat3 rotation_ = Mat3::Identity();
  Mat3 streaming_ = Mat3::Zero();  //!< velocity gradient currently in the grain velocities
  double particle_steps_ = 0.0;
  double last_mean_stress_ = 0.0;
  Mat3 strain_ = Mat3::Zero();
  //! EngineRun::continued: the engine's fix deform left in place by the last run; while it is,
  //! the next continued update runs without a set-up.
  bool deform_fix_kept_ = false;
};

//! How an update of an RVE of `spec` runs its engine: continued between set-ups where
//! `setup_every` > 1 (the caller calls require_setup() once in setup_every updates).
inline Rve::EngineRun update_engine_run(const RveSpec& spec) {
  return spec.setup_every > 1 ? Rve::EngineRun::continued : Rve::EngineRun::set_up;
}

//! Whether update `update` (counted from 0) of an RVE of `spec` opens a period of
//! `setup_every` updates: the engine sets up before it, and only there may the RVE move between
//! ranks or be checkpointed exactly.
inline bool starts_setup_period(const RveSpec& spec, long update) {
  return update % spec.setup_every == 0;
}

}  // namespace mpm_lig::rve
