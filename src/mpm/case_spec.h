#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/case_node.h"
#include "core/tensor.h"
#include "materials/material.h"
#include "mpm/material_set.h"
#include "mpm/time_function.h"

namespace mpm_lig::mpm {

//! An axis-aligned box; `min`/`max` have `dimension` entries.
struct Box {
  std::vector<double> min, max;
  bool contains(const double* x, int dimension, double tolerance) const;
};

//! A set of grid nodes: those in a box, or those on a face of the grid.
struct NodeSelector {
  bool by_face = false;
  Box box;
  int axis = 0;        //!< face normal axis
  bool upper = false;  //!< face at the upper end of `axis`
};

//! A velocity constraint on a node set (fixed, roller, or prescribed velocity).
struct Constraint {
  enum class Type { fixed, roller, velocity, rotation };
  Type type = Type::fixed;
  NodeSelector nodes;
  int direction = 0;      //!< roller and velocity: the constrained axis
  double velocity = 0.0;  //!< velocity: value times `function(t)` [m/s]
  //! rotation: v = ω × (x − center) × `function(t)` on every component; ω [rad/s] is
  //! (0, 0, ω_z) in 2D.
  std::vector<double> center;
  Vec3 angular_velocity = Vec3::Zero();
  TimeFunction function;
  int case_index = 0;  //!< position in boundary_conditions (names its history columns)
};

//! A traction on the material points whose initial position lies in `points`: force per
//! point = traction × point face area (V0^((D-1)/D)) × function(t).
struct Traction {
  Box points;
  std::vector<double> traction;  //!< [Pa], one entry per axis
  TimeFunction function;
};

//! A rigid strip (2D) or rectangular (3D) footing pushed down the last axis.
struct Footing {
  std::vector<double> center;  //!< horizontal centre (D-1 entries)
  std::vector<double> width;   //!< horizontal sizes B (and L in 3D)
  double base = 0.0;           //!< initial height of its base [m]
  double velocity = 0.0;       //!< downward speed times `function(t)` [m/s]
  TimeFunction function;
  bool rough = true;
  //! Put points that enter the footing back on its nearest face (default off; `nodes` only).
  bool keep_points_out = false;
  //! How it acts on the soil: `nodes` holds the grid nodes at and above its base;
  //! `penalty` presses on the points that overlap it, with a force from the overlap, so
  //! that nothing it does depends on the time step (docs/footing_contact.md).
  enum class Contact { nodes, penalty };
  Contact contact = Contact::nodes;
  //! `penalty`: the contact stiffness, in units of the stiffest material's wave modulus
  //! per cell of overlap.
  double penalty_stiffness = 1.0;
  //! `penalty`: press the points under the footprint less half a cell at each edge inside
  //! the mesh (the grid carries a pressed point's force half a cell beyond its box, so the
  //! whole footprint acts as a footing one cell wider); false: the whole footprint.
  bool penalty_edge_inset = true;
  //! `penalty`, rough base: the interface friction angle δ [deg]; a touching point's hold
  //! slides once it would pass tan δ × its normal force. 90: no limit (full adhesion).
  double interface_friction_deg = 90.0;
};

//! Material points filling a box, with an initial velocity.
struct Body {
  int material = 0;  //!< index into MpmCase::materials
  Box box;
  int points_per_cell = 2;
  std::vector<double> velocity;  //!< uniform part
  //! Start stress of every point (Cauchy, tension positive); empty: the material's own.
  std::optional<Mat3> initial_stress;
  //! First axial mode: v += amplitude sin(pi/2 (x_axis - start) / length).
  bool has_profile = false;
  std::vector<double> profile_amplitude;
  int profile_axis = 0;
  double profile_start = 0.0, profile_length = 1.0;
};

//! History columns of a simple-shear run (output.simple_shear): averages over one material's
//! points and the cycle count of the velocity constraint that drives it.
struct SimpleShearOutput {
  bool enabled = false;
  int material = 0;     //!< index into MpmCase::materials
  double period = 0.0;  //!< period of the driving constraint's time function [s]
};

//! RVE snapshots (output.rve_snapshots): the microstructure of the DEM points nearest to
//! chosen positions, at the start, every `every` steps (0: never between) and at the end.
struct RveSnapshotOutput {
  std::vector<std::vector<double>> at;  //!< positions in the initial configuration
  long every = 0;
};

//! Everything an MPM run needs but its materials, validated: dimension-independent plain data
//! (copyable, no live objects).
struct MpmCase {
  std::string title;
  //! The case as read: a checkpoint keeps it, and a resume compares it key by key.
  nlohmann::json document;
  int dimension = 2;

  // analysis
  bool musl = true;
  std::string shape_function = "linear";
  double flip = 1.0;  //!< FLIP fraction of the particle velocity update (1 = FLIP, 0 = PIC)
  double damping = 0.0;
  double mass_scaling = 1.0;
  bool volumetric_smoothing = false;
  //! `analysis.internal_length` (docs/methods.md §7): ℓ [m] (0: off); its method,
  //! "second_gradient" (with the softening modulus G_s [Pa]) or "nonlocal" (with the
  //! non-local weight m).
  double internal_length = 0.0;
  std::string internal_length_method = "second_gradient";
  double softening_modulus = 0.0;
  //! The strain ε_y across ℓ beyond which the gradient relaxes (0: unbounded).
  double gradient_yield_strain = 0.0;
  //! The weight β of the fit's residual energy (0: none; docs/methods.md §7, the odd-even mode).
  double gradient_residual_weight = 0.0;
  double nonlocal_weight = 1.0;
  bool has_second_gradient() const {
    return internal_length > 0.0 && internal_length_method == "second_gradient";
  }
  bool has_bounded_gradient() const { return has_second_gradient() && gradient_yield_strain > 0.0; }
  bool fixed_time_step = false;
  double cfl = 0.5;
  double time_step = 0.0;
  double end_time = 0.0;  //!< 0 when the run ends by step count
  long end_steps = 0;     //!< 0 when the run ends by time
  long gravity_stage_steps = 0;
  double gravity_stage_damping = 0.0;

  // mesh
  std::vector<double> origin, size;
  std::vector<int> cells;
  //! Per axis: the mesh wraps around (mesh.periodic); its two faces are one node plane.
  std::vector<bool> periodic;

  std::vector<double> gravity;
  std::vector<int> material_ids;  //!< the case file's "id" of each material (MaterialSet order)
  std::vector<Body> bodies;
  std::vector<Constraint> constraints;
  std::vector<Traction> tractions;
  std::vector<Footing> footings;

  // output
  long output_every = 100;
  long history_every = 1;
  long checkpoint_every = 0;  //!< main-stage steps between checkpoints; 0: only on SIGTERM
  bool write_fields = true;
  //! results.h5 also holds each point's F and the step's dF (output.deformation_gradient):
  //! what an element test needs to replay a point's path (element/recorded_path.h).
  bool write_deformation = false;
  //! history.csv's `damping_work` (output.damping_work): what the local damping has taken out
  //! of the motion since the main stage began.
  bool record_damping_work = false;
  SimpleShearOutput simple_shear;
  RveSnapshotOutput rve_snapshots;
};

//! A case as read from its file: the plain data and the materials it names, created from their
//! case nodes but not prepared yet (see MaterialSet for the order of a run).
struct MpmProblem {
  MpmCase spec;
  MaterialSet materials;
};

//! Read and validate the whole case (everything but "title" and "analysis.type", which the
//! application reads). Every problem is a CaseError with its JSON path.
MpmProblem read_case(const CaseNode& root, const materials::MaterialRegistry& registry);

}  // namespace mpm_lig::mpm
