#pragma once
// Engine input for the DEM layer tests: the same granular system in LIGGGHTS and LAMMPS
// syntax (Hertz normal contact from Young's modulus and Poisson's ratio, Coulomb friction).

#include <memory>
#include <string>
#include <vector>

#include "core/tensor.h"
#include "dem/engine.h"

namespace mpm_lig::dem::test {

//! Material of every grain.
struct Material {
  double young = 7.0e8;   //!< E [Pa]
  double poisson = 0.3;   //!< ν
  double friction = 0.5;  //!< Coulomb μ
  double restitution = 0.5;
  double density = 2650.0;
};

struct Grain {
  Vec3 x;
  double radius = 0.0;
};

//! Box, material and pair style for `engine` ("liggghts" or "lammps"). `periodic`: p p p
//! (triclinic if a tilt is non-zero), else a fixed box.
std::string setup_script(const std::string& engine, const Box& box, bool periodic,
                         const Material& material);
//! Creates the grains (ids 1..N in order).
std::string grains_script(const std::vector<Grain>& grains, const Material& material);
//! nve/sphere integration, time step, and `compute <id> all pressure thermo_temp virial` (no
//! kinetic part) read by thermo so that the virial is tallied on the last step of every run.
std::string dynamics_script(double timestep, const std::string& pressure_id);

//! A jittered cubic arrangement of n³ grains in the box [0, n·spacing)³ whose diameters
//! (spacing × [1.0, 1.04]) make neighbours overlap slightly: a dense-ish packing under
//! pressure without a consolidation stage.
std::vector<Grain> jittered_packing(int n, double spacing, unsigned seed);

//! An instance of `engine` holding the jittered packing of 4³ grains 10 mm apart (seed 7) in a
//! periodic box tilted by xy = `tilt` × spacing, set up to run (`compute p` its pressure).
std::unique_ptr<Engine> periodic_packing(const std::string& engine, const std::string& label,
                                         double tilt);

}  // namespace mpm_lig::dem::test
