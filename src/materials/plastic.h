#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "materials/continuum.h"
#include "materials/mohr_coulomb_return.h"

namespace mpm_lig::materials {

//! A continuum material with accumulated plastic strains as output state:
//! "plastic_strain" ε_q^p = Σ √(2/3 Δe^p:Δe^p) (deviatoric) and "plastic_volumetric_strain"
//! ε_v^p = Σ tr Δε^p (dilation positive).
class PlasticMaterial : public ContinuumMaterial {
 public:
  using ContinuumMaterial::ContinuumMaterial;

  std::vector<std::string> state_names() const override {
    return {"plastic_strain", "plastic_volumetric_strain"};
  }
  double state(std::size_t point, std::size_t k) const override;
  //! Perfect plasticity: stress and the accumulated plastic strains are the whole state.
  bool checkpointable() const override { return true; }
  void set_state(std::size_t point, std::size_t k, double value) override;

 protected:
  void resize_state(std::size_t count) override { plastic_.resize(count, Eigen::Vector2d::Zero()); }
  //! Accumulate the principal plastic strain increment of a return at `point`.
  void accumulate(std::size_t point, const Vec3& plastic_principal);
  //! Accumulate plastic strain increments given as (Δε_q^p, Δε_v^p).
  void add_plastic(std::size_t point, double deviatoric, double volumetric) {
    plastic_[point] += Eigen::Vector2d(deviatoric, volumetric);
  }

 private:
  std::vector<Eigen::Vector2d> plastic_;  // (ε_q^p, ε_v^p) per point
};

//! Linear softening of a yield value with the accumulated deviatoric plastic strain κ:
//! q_y(κ) = max(q_y0 − H κ, q_r). H = 0 is perfect plasticity.
struct Softening {
  double modulus = 0.0;   //!< H [Pa]
  double residual = 0.0;  //!< q_r [Pa]
};

//! "von_mises": J2 with radial return; yield at q = q_y, perfectly plastic or, with
//! `softening_modulus`, softening linearly to `residual_yield_stress` (the test material of
//! a regularised coupling: docs/methods.md §7).
class VonMises : public PlasticMaterial {
 public:
  VonMises(double density, const Elasticity& elasticity, double yield_stress,
           Softening softening = {})
      : PlasticMaterial(density, elasticity), yield_stress_(yield_stress), softening_(softening) {}
  std::string type() const override { return "von_mises"; }
  double yield_stress() const { return yield_stress_; }
  //! The yield value after a deviatoric plastic strain `kappa`.
  double yield_stress(double kappa) const;

 protected:
  Mat3 correct(std::size_t point, const Mat3& trial) override;

 private:
  double yield_stress_;
  Softening softening_;
};

//! Friction and dilatancy angles falling linearly with the accumulated deviatoric plastic
//! strain κ from the peak (the material's φ, ψ) to residual values reached at κ_r: a dense
//! sand's softening, as a packing's biaxial test measures it. κ_r = 0: no softening.
struct FrictionSoftening {
  double residual_friction = 0.0;   //!< φ_r [rad], in (0, φ]
  double residual_dilatancy = 0.0;  //!< ψ_r [rad], in [0, min(ψ, φ_r)]
  double plastic_strain = 0.0;      //!< κ_r
};

//! "mohr_coulomb" (and "tresca" as its φ = ψ = 0 case): non-associated flow with dilatancy
//! ψ, return in principal stress space (plane, edge, apex); perfectly plastic, or with the
//! angles softening (FrictionSoftening).
class MohrCoulomb : public PlasticMaterial {
 public:
  MohrCoulomb(std::string type, double density, const Elasticity& elasticity,
              const MohrCoulombStrength& strength, const FrictionSoftening& softening = {})
      : PlasticMaterial(density, elasticity),
        type_(std::move(type)),
        strength_(strength),
        softening_(softening) {}

  std::string type() const override { return type_; }
  const MohrCoulombStrength& strength() const { return strength_; }
  //! The strength after a deviatoric plastic strain `kappa` (the peak one without softening).
  MohrCoulombStrength strength(double kappa) const;

 protected:
  Mat3 correct(std::size_t point, const Mat3& trial) override;

 private:
  std::string type_;
  MohrCoulombStrength strength_;
  FrictionSoftening softening_;
};

}  // namespace mpm_lig::materials
