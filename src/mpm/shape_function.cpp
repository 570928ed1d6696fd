#include "mpm/shape_function.h"

#include <cmath>

namespace mpm_lig::mpm {

Weights1d LinearShape::weights(double xi, double /*half_length*/, double cell) const {
  Weights1d w;
  w.first = static_cast<int>(std::floor(xi));
  w.count = 2;
  const double s = xi - w.first;
  w.value = {1.0 - s, s, 0.0};
  w.gradient = {-1.0 / cell, 1.0 / cell, 0.0};
  return w;
}

namespace {

//! uGIMP function of the distance r between point and node, both in cell units.
void gimp_1d(double r, double lp, double& value, double& slope) {
  const double a = std::abs(r);
  const double sign = r < 0.0 ? -1.0 : 1.0;
  if (a < lp) {
    value = 1.0 - (r * r + lp * lp) / (2.0 * lp);
    slope = -r / lp;
  } else if (a < 1.0 - lp) {
    value = 1.0 - a;
    slope = -sign;
  } else if (a < 1.0 + lp) {
    const double g = 1.0 + lp - a;
    value = g * g / (4.0 * lp);
    slope = -sign * g / (2.0 * lp);
  } else {
    value = 0.0;
    slope = 0.0;
  }
}

}  // namespace

Weights1d GimpShape::weights(double xi, double half_length, double cell) const {
  Weights1d w;
  // Nodes with |xi - i| < 1 + lp: at most three when lp < 1/2.
  w.first = static_cast<int>(std::floor(xi - half_length));
  w.count = 3;
  for (int k = 0; k < 3; ++k) {
    double value = 0.0, slope = 0.0;
    gimp_1d(xi - (w.first + k), half_length, value, slope);
    w.value[k] = value;
    w.gradient[k] = slope / cell;
  }
  return w;
}

const ShapeRegistry& shape_registry() {
  static const ShapeRegistry registry = [] {
    ShapeRegistry r;
    r.add("linear", [] { return std::make_unique<LinearShape>(); });
    r.add("gimp", [] { return std::make_unique<GimpShape>(); });
    return r;
  }();
  return registry;
}

}  // namespace mpm_lig::mpm
