#pragma once

#include <string>

#include "materials/plastic.h"

namespace mpm_lig::materials {

//! Cone f = √J2 + η σ_m − ξ c ≤ 0 (σ_m = tr σ / 3, tension positive), plastic potential
//! √J2 + η̄ σ_m, with (η, ξ, η̄) matched to Mohr–Coulomb's c, φ, ψ.
struct DruckerPragerCone {
  double eta = 0.0;       //!< η
  double xi_c = 0.0;      //!< ξ c [Pa]
  double eta_flow = 0.0;  //!< η̄

  //! Which Mohr–Coulomb condition the cone reproduces.
  enum class Match { plane_strain, triaxial_compression, triaxial_extension };
  //! The cone through Mohr–Coulomb (c, φ, ψ): plane_strain gives the same plane-strain
  //! strength for associated flow (η = 3 tan φ / √(9 + 12 tan² φ), ξ = 3 / √(…));
  //! triaxial_compression / _extension touch its outer / inner corners.
  static DruckerPragerCone matched(Match match, double cohesion, double friction, double dilatancy);
};

//! "drucker_prager": perfectly plastic Drucker–Prager cone, return to the cone or its apex.
class DruckerPrager : public PlasticMaterial {
 public:
  DruckerPrager(double density, const Elasticity& elasticity, const DruckerPragerCone& cone)
      : PlasticMaterial(density, elasticity), cone_(cone) {}
  std::string type() const override { return "drucker_prager"; }
  const DruckerPragerCone& cone() const { return cone_; }

 protected:
  Mat3 correct(std::size_t point, const Mat3& trial) override;

 private:
  DruckerPragerCone cone_;
};

}  // namespace mpm_lig::materials
