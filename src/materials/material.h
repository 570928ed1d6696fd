#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/case_node.h"
#include "core/registry.h"
#include "core/tensor.h"

namespace mpm_lig::materials {

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
  //! Mass density [kg/m^3].
  virtual double density() const = 0;
  //! Largest constrained (P-wave) modulus the material can show [Pa]: sets the CFL time step.
  virtual double wave_modulus() const = 0;

  //! Add `count` points with zero stress and fresh state; returns the index of the first.
  virtual std::size_t add_points(std::size_t count) = 0;
  //! Impose an initial stress (for example K0) on one point, where the material allows it.
  virtual void set_stress(std::size_t point, const Mat3& sigma) = 0;

  //! Advance `points` by their deformation increments `dF` (F_new = dF F_old, spin
  //! included) over `dt`, and write their new Cauchy stresses (tension positive) to `stress`.
  virtual void update(const std::vector<std::size_t>& points, const std::vector<Mat3>& dF,
                      double dt, std::vector<Mat3>& stress) = 0;

  //! Names of per-point scalar state variables for output (e.g. "plastic_strain").
  virtual std::vector<std::string> state_names() const { return {}; }
  //! Value of state variable `k` of `point`.
  virtual double state(std::size_t /*point*/, std::size_t /*k*/) const { return 0.0; }
};

//! Creates a material from its case node (`materials[i]`); the node's "type" picks the entry.
using MaterialRegistry = Registry<Material, const CaseNode&>;

//! The continuum materials shipped with mpm_lig.
void register_materials(MaterialRegistry& registry);

}  // namespace mpm_lig::materials
