#include "materials/elasticity.h"

#include <cmath>
#include <sstream>

namespace mpm_lig::materials {
namespace {

std::string text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

double read_open_range(const CaseNode& node, const std::string& key, double lo, double hi) {
  const double value = node.get<double>(key);
  if (!(value > lo && value < hi))
    node.fail(key, "must be > " + text(lo) + " and < " + text(hi) + ", got " + text(value));
  return value;
}

Elasticity Elasticity::from_moduli(double youngs_modulus, double poisson_ratio) {
  Elasticity e;
  e.youngs_modulus = youngs_modulus;
  e.poisson_ratio = poisson_ratio;
  e.bulk = youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio));
  e.shear = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  e.lame = e.bulk - 2.0 * e.shear / 3.0;
  return e;
}

Elasticity Elasticity::read(const CaseNode& node) {
  const double youngs = node.positive("youngs_modulus");
  const double poisson = read_open_range(node, "poisson_ratio", -1.0, 0.5);
  return from_moduli(youngs, poisson);
}

}  // namespace mpm_lig::materials
