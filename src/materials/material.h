#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <mpi.h>

#include "core/case_node.h"
#include "core/registry.h"
#include "core/resources.h"
#include "core/tensor.h"
#include "core/test_hooks.h"
#include "materials/checkpoint_io.h"
#include "materials/statistics.h"

namespace mpm_lig::materials {

//! What a material gets before the run: the ranks it may spread over and a folder of its own.
struct MaterialContext {
  MPI_Comm comm = MPI_COMM_WORLD;  //!< every rank of the run (the MPM is replicated on all)
  std::string work_dir;            //!< for files the material makes (packings); may not exist yet
  TestHooks hooks;                 //!< fault injection asked for by the tests
};

//! What a material receives for one MPM step: a batch of its points and their deformation
//! increments, in the same order. Whatever a material may need of the step is a member here,
//! so that a new input reaches every material without changing update()'s signature.
struct MaterialStep {
  const std::vector<std::size_t>& points;  //!< the material's own point indices
  //! One increment per point: F_new = dF F_old, spin included (after the MPM's kinematics
  //! operators, docs/DESIGN.md §6).
  const std::vector<Mat3>& dF;
  double dt;  //!< the step [s]
};

//! The constitutive side of a material point, seen by the MPM solver.
//!
//! Batch-shaped on purpose: the solver hands over all points of a material at once, so
//! that the DEM RVE material can spread them over MPI ranks. A material owns the state of
//! its points (stress, plastic strain, or a whole DEM packing); the solver keeps a copy of
//! the stress it returned. All tensors are 3x3 (plane strain: zero out-of-plane increment).
class Material {
 public:
  virtual ~Material() = default;

  //! Registered type name ("linear_elastic", "mohr_coulomb", ...).
  virtual std::string type() const = 0;

  //! Collective over `context.comm`, called on every rank before density(), wave_modulus()
  //! and add_points(): a DEM material makes its packings here.
  virtual void prepare(const MaterialContext& /*context*/) {}
  //! Case-level check (`node` is the material's case node): fails with a CaseError when the
  //! material cannot serve an analysis of this dimension.
  virtual void check_dimension(const CaseNode& /*node*/, int /*dimension*/) const {}
  //! Checks against the run before anything is created (`mpm_lig --validate` too): `points`
  //! of this material on `ranks` MPI ranks, writing into `run_dir`. Adds to `budget` the memory
  //! one rank needs for them beyond the MPM's own copy of the points; a CaseError naming the
  //! material's JSON path when it cannot serve them.
  virtual void check_run(std::size_t /*points*/, int /*ranks*/, const std::string& /*run_dir*/,
                         MemoryBudget& /*budget*/) const {}
  //! Mass density [kg/m^3].
  virtual double density() const = 0;
  //! Largest constrained (P-wave) modulus the material can show [Pa]: sets the CFL time step.
  virtual double wave_modulus() const = 0;
  //! The constrained modulus of its stiffest point now [Pa], from state every rank holds:
  //! wave_modulus() unless the material stiffens with its state (a packing with its pressure).
  virtual double current_wave_modulus() const { return wave_modulus(); }
  //! Largest CFL number (time step over cell / wave speed) at which explicit MPM with this
  //! material was measured stable: 1 for a material whose wave_modulus() bounds its stiffness.
  virtual double max_cfl() const { return 1.0; }

  //! Add `count` points with zero stress and fresh state; returns the index of the first.
  virtual std::size_t add_points(std::size_t count) = 0;
  //! The stress `point` starts with (a DEM point: its consolidated packing's); zero by default.
  virtual Mat3 initial_stress(std::size_t /*point*/) const { return Mat3::Zero(); }
  //! Impose an initial stress (for example K0) on one point, where the material allows it.
  virtual void set_stress(std::size_t point, const Mat3& sigma) = 0;
  //! Whether set_stress() can give its points a start stress (a DEM point's is its packing's).
  virtual bool accepts_initial_stress() const { return true; }
  //! Put back a stress this material computed itself (a resumed run), bit for bit.
  virtual void restore_stress(std::size_t point, const Mat3& sigma) { set_stress(point, sigma); }

  //! Advance `step.points` by their increments `step.dF` over `step.dt`, and write their new
  //! Cauchy stresses (tension positive) to `stress`, one per point in the batch's order.
  virtual void update(const MaterialStep& step, std::vector<Mat3>& stress) = 0;

  //! Names of per-point scalar state variables for output (e.g. "plastic_strain").
  virtual std::vector<std::string> state_names() const { return {}; }
  //! Value of state variable `k` of `point`.
  virtual double state(std::size_t /*point*/, std::size_t /*k*/) const { return 0.0; }
  //! Whether write_checkpoint() saves everything a point's future depends on. By default that
  //! holds when the stress is the whole state (no state_names()).
  virtual bool checkpointable() const { return state_names().empty(); }
  //! Whether a checkpoint written now resumes bit-identically. A material that carries more
  //! between two updates than its checkpoint holds (a DEM material continuing its engines' runs
  //! between set-ups) says no until it is back at a set-up; the run then writes its checkpoint
  //! at the first step where every material says yes.
  virtual bool at_exact_checkpoint() const { return true; }
  //! Restore state variable `k` of `point` (used by the default restore_checkpoint()).
  virtual void set_state(std::size_t /*point*/, std::size_t /*k*/, double /*value*/) {
    throw std::logic_error(type() + ": set_state() on a material without restorable state");
  }
  //! Collective: save the state of this material's `points` points beyond the stresses the
  //! MPM saves itself. Default: the state_names() values, point by point ("state").
  virtual void write_checkpoint(CheckpointWriter& out, std::size_t points);
  //! Collective, on a freshly prepared material with its points added and before any update:
  //! take back what write_checkpoint() saved; `stress[i]` is point i's saved stress. Throws
  //! naming the checkpoint when it does not fit this material. Default: restore_stress() and
  //! set_state() from "state".
  virtual void restore_checkpoint(const CheckpointReader& in, const std::vector<Mat3>& stress);
  //! Named statistics of the run so far for summary.json (materials/statistics.h): a DEM
  //! material's costs; none for continuum laws.
  virtual Report report() const { return {}; }
};

//! A material whose points have a microstructure to draw (a DEM point's RVE), besides being a
//! Material: the MPM finds it with snapshots_of(), so Material itself has no hook for it.
class MicrostructureSnapshots {
 public:
  virtual ~MicrostructureSnapshots() = default;
  //! Collective over the material's communicator: write `point`'s microstructure as
  //! PREFIX_{grains,contacts,cell}.vtk.
  virtual void write_snapshot(std::size_t point, const std::string& prefix) = 0;
};

//! `material`'s snapshots, null when its points have no microstructure to draw.
inline MicrostructureSnapshots* snapshots_of(Material& material) {
  return dynamic_cast<MicrostructureSnapshots*>(&material);
}
inline bool has_snapshots(const Material& material) {
  return dynamic_cast<const MicrostructureSnapshots*>(&material) != nullptr;
}

//! Creates a material from its case node (`materials[i]`); the node's "type" picks the entry.
//! A family whose materials report statistics registers them here at their zero values, so
//! that every run's summary holds them, a run without such a material too.
class MaterialRegistry : public Registry<Material, const CaseNode&> {
 public:
  void add_statistics(const Report& zero) {
    statistics_.values.insert(statistics_.values.end(), zero.values.begin(), zero.values.end());
    statistics_.derived.insert(statistics_.derived.end(), zero.derived.begin(), zero.derived.end());
  }
  //! Every registered family's statistics at their zero values.
  const Report& statistics() const { return statistics_; }

 private:
  Report statistics_;
};

//! The continuum materials shipped with mpm_lig.
void register_materials(MaterialRegistry& registry);

}  // namespace mpm_lig::materials
