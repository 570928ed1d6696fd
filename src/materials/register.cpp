// The continuum materials: one place that maps case-file names to laws and reads their keys.
// Every key is documented in README.md, section "Materials".

#include <algorithm>
#include <cmath>
#include <memory>

#include "materials/drucker_prager.h"
#include "materials/linear_elastic.h"
#include "materials/material.h"
#include "materials/plastic.h"

namespace mpm_lig::materials {
namespace {

std::unique_ptr<Material> read_linear_elastic(const CaseNode& node) {
  const double density = node.positive("density");
  return std::make_unique<LinearElastic>(density, Elasticity::read(node));
}

std::unique_ptr<Material> read_von_mises(const CaseNode& node) {
  const double density = node.positive("density");
  const Elasticity elasticity = Elasticity::read(node);
  const double yield_stress = node.positive("yield_stress");
  Softening softening;
  if (node.has("softening_modulus")) {
    // H ≥ 3G would make the return itself snap back (q − 3GΔε falls no faster than q_y).
    softening.modulus = node.in_range("softening_modulus", 0.0, 3.0 * elasticity.shear);
    if (!(softening.modulus < 3.0 * elasticity.shear))
      node.fail("softening_modulus", "must be below 3G (three times the shear modulus)");
    softening.residual = node.in_range_or("residual_yield_stress", 0.0, yield_stress, 0.0);
  } else if (node.has("residual_yield_stress")) {
    node.fail("residual_yield_stress", "needs \"softening_modulus\"");
  }
  return std::make_unique<VonMises>(density, elasticity, yield_stress, softening);
}

//! Tresca is Mohr–Coulomb with φ = ψ = 0 and c = c_u: its principal-space return is then
//! exact Tresca (hexagonal prism), not a von Mises match.
std::unique_ptr<Material> read_tresca(const CaseNode& node) {
  const double density = node.positive("density");
  const Elasticity elasticity = Elasticity::read(node);
  MohrCoulombStrength strength;
  strength.cohesion = node.positive("undrained_strength");
  return std::make_unique<MohrCoulomb>("tresca", density, elasticity, strength);
}

//! c, φ, ψ as Mohr–Coulomb and Drucker–Prager read them.
MohrCoulombStrength read_friction(const CaseNode& node) {
  MohrCoulombStrength strength;
  strength.cohesion = node.non_negative("cohesion");
  const double friction_deg = read_open_range(node, "friction_deg", 0.0, 90.0);
  strength.friction = friction_deg * kDegree;
  strength.dilatancy = node.in_range_or("dilatancy_deg", 0.0, friction_deg, 0.0) * kDegree;
  return strength;
}

std::unique_ptr<Material> read_mohr_coulomb(const CaseNode& node) {
  const double density = node.positive("density");
  const Elasticity elasticity = Elasticity::read(node);
  MohrCoulombStrength strength = read_friction(node);
  if (node.has("tension_cutoff")) {
    // Beyond the apex c cot φ the cutoff would never act: reject it rather than ignore it.
    strength.tension_cutoff = node.in_range("tension_cutoff", 0.0, strength.apex());
  }
  FrictionSoftening softening;
  if (node.has("softening")) {
    // The cutoff is checked against the peak's apex; a softened φ moves the apex outward
    // (c cot φ grows as φ falls), so it stays inside.
    const CaseNode soft = node.child("softening");
    const double peak_deg = strength.friction / kDegree;
    const double residual_deg = soft.in_range("residual_friction_deg", 0.0, peak_deg);
    if (!(residual_deg > 0.0))
      soft.fail("residual_friction_deg", "must be above 0");
    softening.residual_friction = residual_deg * kDegree;
    const double dilatancy_cap = std::min(strength.dilatancy / kDegree, residual_deg);
    softening.residual_dilatancy =
        soft.in_range_or("residual_dilatancy_deg", 0.0, dilatancy_cap, 0.0) * kDegree;
    softening.plastic_strain = soft.positive("plastic_strain");
  }
  return std::make_unique<MohrCoulomb>("mohr_coulomb", density, elasticity, strength, softening);
}

std::unique_ptr<Material> read_drucker_prager(const CaseNode& node) {
  using Match = DruckerPragerCone::Match;
  const double density = node.positive("density");
  const Elasticity elasticity = Elasticity::read(node);
  const MohrCoulombStrength s = read_friction(node);
  const std::string match =
      node.choice("match", {"plane_strain", "triaxial_compression", "triaxial_extension"});
  const Match kind = match == "plane_strain"           ? Match::plane_strain
                     : match == "triaxial_compression" ? Match::triaxial_compression
                                                       : Match::triaxial_extension;
  const DruckerPragerCone cone =
      DruckerPragerCone::matched(kind, s.cohesion, s.friction, s.dilatancy);
  return std::make_unique<DruckerPrager>(density, elasticity, cone);
}

}  // namespace

void register_materials(MaterialRegistry& registry) {
  registry.add("linear_elastic", read_linear_elastic);
  registry.add("von_mises", read_von_mises);
  registry.add("tresca", read_tresca);
  registry.add("mohr_coulomb", read_mohr_coulomb);
  registry.add("drucker_prager", read_drucker_prager);
}

}  // namespace mpm_lig::materials
