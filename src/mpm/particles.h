#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "core/tensor.h"
#include "mpm/case_spec.h"

namespace mpm_lig::mpm {

//! The material points, structure of arrays. Tensors are 3x3 in 2D too (plane strain:
//! zero out-of-plane deformation, the out-of-plane stress is the material's answer).
template <int D>
struct Particles {
  using Vec = Eigen::Matrix<double, D, 1>;

  std::size_t size() const { return position.size(); }

  std::vector<Vec> position;
  std::vector<Vec> reference;  //!< position at the start of the main stage
  std::vector<Vec> velocity;
  std::vector<Vec> half_length;             //!< half size in cell units (GIMP); fixed
  std::vector<Vec> external_force;          //!< tractions, rebuilt every step [N]
  std::vector<double> mass;                 //!< true mass [kg]
  std::vector<double> volume;               //!< current volume [m^D]
  std::vector<double> volume0;              //!< initial volume
  std::vector<Mat3> deformation;            //!< deformation gradient F
  std::vector<Mat3> stress;                 //!< Cauchy stress, tension positive [Pa]
  std::vector<int> material;                //!< index into the case's materials
  std::vector<std::size_t> material_point;  //!< index of the point inside its material
  std::vector<int> body;
};

//! Fill every body's box with points (points_per_cell per cell and axis, equally spaced,
//! filling the box exactly), register them with their materials, set initial velocities.
template <int D>
Particles<D> generate_particles(const MpmCase& c, MaterialSet& materials);

}  // namespace mpm_lig::mpm
