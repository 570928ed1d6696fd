#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/case_node.h"

namespace mpm_lig::rve {

//! Grain radii: uniform in [min, max], or a piecewise-linear cumulative distribution by number.
struct RadiusSpec {
  double min = 0.0;
  double max = 0.0;
  std::vector<double> radii;       //!< distribution support points (ascending), empty: uniform
  std::vector<double> cumulative;  //!< cumulative number fraction at `radii` (0 ... 1)
  double mean() const;             //!< number-mean radius
};

//! Contact law (Hertz–Mindlin); optional effects appear in the engine input only when set.
struct ContactSpec {
  double youngs_modulus = 0.0;  //!< [Pa]
  double poisson_ratio = 0.0;
  double friction = 0.0;                          //!< sliding friction coefficient μ
  double restitution = 0.0;                       //!< normal coefficient of restitution
  std::optional<double> rolling_friction;         //!< rolling resistance coefficient μ_r
  std::optional<double> cohesion_energy_density;  //!< [J/m^3], LIGGGHTS sjkr only
};

//! Preparation of a fresh packing (ignored when the RVE starts from a restart file).
struct PreparationSpec {
  double confining_pressure = 0.0;          //!< isotropic target p [Pa]
  std::optional<double> target_void_ratio;  //!< reached by lowering friction while compacting
  //! Friction coefficient of the first consolidation (a higher one packs looser, so that the
  //! staged lowering can reach a looser target); none: the contact law's.
  std::optional<double> consolidation_friction;
  double tolerance = 0.005;             //!< relative pressure tolerance at the end
  double void_ratio_tolerance = 0.005;  //!< allowed |reached - target void ratio|
  double initial_solid_fraction = 0.0;  //!< of the loose random packing
  double max_strain_rate = 0.0;         //!< servo strain rate limit [1/s]
  long max_steps = 0;                   //!< DEM step budget for the whole preparation
  //! DEM time step of the preparation [s]: the RVE's own unless given, so that a packing can be
  //! loaded at another step than the one it was made with (docs/dem_work.md §11).
  double time_step = 0.0;
};

//! How many DEM steps one deformation increment takes.
struct SubstepSpec {
  int fixed = 0;                 //!< > 0: exactly this many
  double inertial_number = 0.0;  //!< otherwise from I = γ̇ d sqrt(ρ/p)
  int min = 1;
  int max = 0;
  //! The mean stress the rule counts at least [Pa]: as p → 0 (liquefied, dilated, unloaded
  //! packings) the quasi-static rule asks for ever more sub-steps (docs/dem_work.md).
  double pressure_floor = 1e3;
  //! Once the net shear strain γ an RVE has run (Rve::net_shear) reaches `sheared_after`, the
  //! rule targets `sheared_inertial_number` instead: past its peak a packing's stress ratio
  //! hardly depends on I, its peak does (docs/dem_work.md §8). 0: off.
  double sheared_after = 0.0;
  double sheared_inertial_number = 0.0;
};

//! Everything needed to build, prepare and drive one RVE (the "rve" node of a case, and
//! later `materials[i]` of type "dem_rve").
struct RveSpec {
  std::string path;                 //!< JSON path of the node, for messages
  std::string engine = "liggghts";  //!< "liggghts" | "lammps"
  int dimension = 3;                //!< 2: discs in a plane (enforce2d), 3: spheres
  long grains = 0;
  RadiusSpec radius;
  double density = 0.0;  //!< grain density [kg/m^3]
  std::uint64_t seed = 1;
  ContactSpec contact;
  double time_step = 0.0;  //!< DEM time step [s] (resolved from a Rayleigh fraction if asked)
  double rayleigh_time_step = 0.0;
  PreparationSpec preparation;
  std::string restart_file;  //!< start from this engine restart instead of preparing
  SubstepSpec substeps;
  bool stream_velocity = true;  //!< affine motion by streaming velocity (remap v) or remap x
  //! The engine's full set-up (`run … pre yes`) before one update in `setup_every`; the updates
  //! between continue its run without it (Engine::run_continued). 1: before every update.
  int setup_every = 1;
  //! Angle from the physical x axis to the periodic cell's first side [rad], about z. A shear
  //! band fits a periodic cell only along its lattice directions, and with the cell's whole
  //! width between its images only along a side (docs/methods.md §7): 0 keeps the cell on the
  //! physical axes.
  double cell_angle = 0.0;
  double thickness = 0.0;          //!< 2D: out-of-plane thickness that turns N/m into Pa
  double max_kinetic_ratio = 1.0;  //!< health limit on kinetic / elastic energy ...
  double max_flow_ratio = 1000.0;  //!< ... together with kinetic / flow energy
  std::string log_file;            //!< engine log for debugging ("" = none)
};

//! Smallest accepted grain count: fewer grains do not make a representative packing and the
//! periodic cell gets smaller than the neighbour cut-off.
inline constexpr long kMinGrains = 50;

//! Read and validate an RVE node; every problem is a CaseError naming its JSON path.
RveSpec parse_rve_spec(const CaseNode& node);

//! Memory of one engine instance holding this RVE [bytes], from measurements of idle
//! 400-grain instances (docs/DESIGN.md: 1.1 MB in LIGGGHTS, 1.95 MB in LAMMPS), taken as
//! proportional to the grain count.
double instance_memory_bytes(const RveSpec& spec);

//! Rayleigh time step of the smallest grain [s].
double rayleigh_time_step(const RveSpec& spec);

}  // namespace mpm_lig::rve
