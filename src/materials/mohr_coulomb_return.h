#pragma once

#include <limits>

#include "core/tensor.h"
#include "materials/elasticity.h"

namespace mpm_lig::materials {

//! Strength of a Mohr–Coulomb material (tension positive). φ = ψ = 0 is Tresca.
struct MohrCoulombStrength {
  double cohesion = 0.0;   //!< c [Pa]
  double friction = 0.0;   //!< φ [rad], in [0, π/2)
  double dilatancy = 0.0;  //!< ψ [rad], in [0, φ]
  //! Largest principal stress allowed, σ_t [Pa]; infinity when only the cone's apex limits it.
  double tension_cutoff = std::numeric_limits<double>::infinity();

  //! f = (σ1 − σ3) + (σ1 + σ3) sin φ − 2 c cos φ for σ1 ≥ σ3: ≤ 0 is admissible.
  double yield(const Vec3& sorted) const;
  //! Whether sorted principal stresses are inside the yield surface and the cutoff, up to
  //! a round-off tolerance relative to the stress level (the return's own test).
  bool admissible(const Vec3& sorted) const;
  //! Mean stress of the cone's apex, c cot φ (infinity for φ = 0).
  double apex() const;
};

//! Which part of the yield surface the return landed on.
enum class ReturnKind { elastic, plane, edge, apex, tension };

//! Closest-point (in the energy norm) return of sorted principal trial stresses
//! σ1 ≥ σ2 ≥ σ3 for perfect plasticity, with flow potential of dilatancy angle ψ.
//!
//! Tried in order: the main plane; the edge it runs off to (σ1 = σ2 or σ2 = σ3), two
//! multipliers from a 2x2 solve; the apex (φ > 0). All are linear, so each is exact. A
//! tension cutoff is applied after it as a Rankine return on the principal stresses above
//! σ_t, which lowers f and keeps the state admissible.
Vec3 mohr_coulomb_return(const Vec3& trial, const Elasticity& elasticity,
                         const MohrCoulombStrength& strength, ReturnKind* kind = nullptr);

//! Principal plastic strain increment D^-1 (trial − returned) of a principal return.
Vec3 plastic_strain(const Vec3& trial, const Vec3& returned, const Elasticity& elasticity);

}  // namespace mpm_lig::materials
