// The continuum materials: one place that maps case-file names to laws and reads their keys.
// Every key is documented in README.md, section "Materials".

#include <cmath>
#include <memory>

#include "materials/linear_elastic.h"
#include "materials/material.h"
#include "materials/plastic.h"

namespace mpm_lig::materials {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

std::unique_ptr<Material> read_linear_elastic(const CaseNode& node) {
  const double density = node.positive("density");
  return std::make_unique<LinearElastic>(density, Elasticity::read(node));
}

std::unique_ptr<Material> read_von_mises(const CaseNode& node) {
  const double density = node.positive("density");
  const Elasticity elasticity = Elasticity::read(node);
  return std::make_unique<VonMises>(density, elasticity, node.positive("yield_stress"));
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

std::unique_ptr<Material> read_mohr_coulomb(const CaseNode& node) {
  const double density = node.positive("density");
  const Elasticity elasticity = Elasticity::read(node);
  MohrCoulombStrength strength;
  strength.cohesion = node.non_negative("cohesion");
  const double friction_deg = read_open_range(node, "friction_deg", 0.0, 90.0);
  strength.friction = friction_deg * kDegree;
  strength.dilatancy = node.in_range_or("dilatancy_deg", 0.0, friction_deg, 0.0) * kDegree;
  if (node.has("tension_cutoff")) {
    // Beyond the apex c cot φ the cutoff would never act: reject it rather than ignore it.
    strength.tension_cutoff = node.in_range("tension_cutoff", 0.0, strength.apex());
  }
  return std::make_unique<MohrCoulomb>("mohr_coulomb", density, elasticity, strength);
}

}  // namespace

void register_materials(MaterialRegistry& registry) {
  registry.add("linear_elastic", read_linear_elastic);
  registry.add("von_mises", read_von_mises);
  registry.add("tresca", read_tresca);
  registry.add("mohr_coulomb", read_mohr_coulomb);
}

}  // namespace mpm_lig::materials
