#pragma once

#include <vector>

#include "core/tensor.h"
#include "dem/engine.h"

namespace mpm_lig::rve {

//! What one look at an RVE tells (all in the physical frame).
struct Observables {
  Mat3 stress = Mat3::Zero();        //!< Cauchy stress, tension positive [Pa]
  double void_ratio = 0.0;           //!< (cell - solid) / solid; areas in 2D
  double coordination_number = 0.0;  //!< 2 N_contacts / N_grains
  double kinetic_energy = 0.0;       //!< fluctuations + rotations of grains in contact [J]
  double elastic_energy = 0.0;       //!< normal Hertz energy Σ 2/5 F_n δ [J]
  long contacts = 0;
  double mean_overlap_strain = 0.0;  //!< mean overlap / branch length over contacts
  double max_overlap_ratio = 0.0;    //!< largest overlap / radius of the smaller grain
  double max_speed_ratio = 0.0;      //!< largest fluctuation speed / own radius [1/s]
  double step_travel = 0.0;          //!< max_speed_ratio × DEM time step: radii per step
  //! Kinetic energy of grains moving at the imposed strain rate over one grain diameter,
  //! ½ Σ m (|L| d)²: the agitation a sheared packing has without any contact force [J].
  double flow_energy = 0.0;
  long grains = 0;
  //! kinetic / elastic energy (0 at rest, infinite moving without contacts): ≪ 1 means
  //! quasi-static.
  double kinetic_ratio() const;
  //! kinetic / flow energy (0 at rest, infinite moving without an imposed strain rate).
  double flow_ratio() const;
};

//! Health limits that do not depend on the stress level (a liquefied packing stays far from
//! them; a numerical blow-up crosses them): radii a grain may travel in one DEM step, and the
//! overlap of two grains against the smaller radius.
inline constexpr double kMaxStepTravel = 0.05;
inline constexpr double kMaxOverlapRatio = 0.5;

//! Grain state gathered from an engine, ordered by grain id.
struct GrainState {
  std::vector<Vec3> x, v, omega;
  std::vector<double> radius, mass;
};
GrainState gather_grains(dem::Engine& engine);

//! Σ branch ⊗ force / volume over `contacts` (tension positive, the engine's frame; not
//! symmetrised: its upper components are what the engine's virial reports).
Mat3 contact_stress(const std::vector<dem::Contact>& contacts, double volume);

//! Contact count, coordination and energies. `streaming` is the affine velocity gradient
//! of the grains (removed before the kinetic energy), `origin` the point where it is zero.
void add_grain_measures(const GrainState& grains, const std::vector<dem::Contact>& contacts,
                        const Mat3& streaming, const Vec3& origin, Observables& out);

//! What check_blow_up reads, from the overlapping pairs instead of the contacts: grains,
//! largest overlap and the motion measures (a grain is loaded when it overlaps another, as a
//! contact with a normal force). Contacts, coordination and the contact energies stay 0.
void add_health_measures(const GrainState& grains, const std::vector<dem::Overlap>& overlaps,
                         const Mat3& streaming, const Vec3& origin, Observables& out);

//! Kinetic, flow energy and largest speed; `loaded[i]` marks grain i as in contact (only those
//! count in the kinetic energy).
void add_motion_measures(const GrainState& grains, const std::vector<char>& loaded,
                         const Mat3& streaming, const Vec3& origin, Observables& out);

}  // namespace mpm_lig::rve
