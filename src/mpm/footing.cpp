#include "mpm/footing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpm_lig::mpm {

FootingSpan footing_span(double center, double width, double origin, double size, double inset,
                         double tol) {
  constexpr double far = std::numeric_limits<double>::infinity();
  FootingSpan s;
  s.lo = std::max(center - 0.5 * width, origin);
  s.hi = std::min(center + 0.5 * width, origin + size);
  s.pressed_lo = s.lo > origin + tol ? s.lo + inset : -far;
  s.pressed_hi = s.hi < origin + size - tol ? s.hi - inset : far;
  return s;
}

template <int D>
RigidFooting<D>::RigidFooting(const Footing& spec, const Grid<D>& grid) : spec_(spec) {
  const double tol = 1e-9 * grid.min_cell();
  for (int d = 0; d < D - 1; ++d) {
    const double inset = spec.penalty_edge_inset ? 0.5 * grid.cell()[d] : 0.0;
    const FootingSpan span =
        footing_span(spec.center[d], spec.width[d], grid.origin()[d], grid.size()[d], inset, tol);
    area_ *= span.hi - span.lo;
    pressed_lo_[d] = span.pressed_lo;
    pressed_hi_[d] = span.pressed_hi;
  }
  for (long id = 0; id < static_cast<long>(grid.node_count()); ++id) {
    const Vec x = grid.node_position(id);
    // Share of the node's tributary length [x - h/2, x + h/2] (clipped to the mesh) that
    // lies under the footing, per axis.
    double share = 1.0;
    for (int d = 0; d < D - 1; ++d) {
      const double h = grid.cell()[d], end = grid.origin()[d] + grid.size()[d];
      const double lo = std::max(x[d] - 0.5 * h, grid.origin()[d]);
      const double hi = std::min(x[d] + 0.5 * h, end);
      const double under = std::min(hi, spec.center[d] + 0.5 * spec.width[d]) -
                           std::max(lo, spec.center[d] - 0.5 * spec.width[d]);
      share *= std::clamp(under / (hi - lo), 0.0, 1.0);
    }
    if (share > tol) {
      footprint_.push_back(id);
      share_.push_back(share);
    }
  }
}

template <int D>
void RigidFooting<D>::apply(Grid<D>& grid, double t, double scale, double dt, bool record) {
  constexpr int up = D - 1;
  const double h = grid.cell()[up];
  const double vf = -speed(t, scale);
  const double base_now = base();
  Vec reaction = Vec::Zero();
  for (std::size_t k = 0; k < footprint_.size(); ++k) {
    const long node = footprint_[k];
    const double m = grid.mass[node];
    if (m <= 0.0)
      continue;
    const double y = grid.origin()[up] + grid.node_index(node)[up] * h;
    const double w = share_[k] * std::clamp(1.0 - (base_now - y) / h, 0.0, 1.0);
    Vec& v = grid.velocity_new[node];
    if (w <= 0.0 || v[up] <= vf)  // not reached, or the material moves away from the base
      continue;
    const Vec trial = v;
    Vec held = Vec::Zero();
    v[up] = (1.0 - w) * v[up] + w * vf;
    held[up] = w;
    if (spec_.rough) {
      for (int d = 0; d < up; ++d) {
        v[d] = (1.0 - w) * v[d];
        held[d] = w;
      }
    }
    // As for node constraints: the footing also takes the damping force on what it imposes,
    // else the load would carry the damping (up to a factor 1 + damping).
    reaction += m * (v - trial) / dt + held.cwiseProduct(grid.damping[node]);
  }
  if (record) {
    load_ = -reaction[up];
    reaction_ = reaction;
  }
}

template <int D>
void RigidFooting<D>::advance(double t, double scale, double dt) {
  settlement_ += speed(t, scale) * dt;
}

template <int D>
void RigidFooting<D>::push_out(Vec& x, Vec& v, double t, double scale, double dt) const {
  constexpr int up = D - 1;
  const double vf = speed(t, scale);
  const double base_next = base() - vf * dt;
  // Depth inside through each face: the base, and each side of the footprint.
  int nearest = up;
  double depth = x[up] - base_next;
  for (int d = 0; d < up; ++d) {
    const double side = 0.5 * spec_.width[d] - std::abs(x[d] - spec_.center[d]);
    if (side < depth) {
      depth = side;
      nearest = d;
    }
  }
  if (depth <= 0.0)
    return;
  if (nearest == up) {
    x[up] = base_next;
    v[up] = std::min(v[up], -vf);
    return;
  }
  const double outward = x[nearest] >= spec_.center[nearest] ? 1.0 : -1.0;
  x[nearest] = spec_.center[nearest] + outward * 0.5 * spec_.width[nearest];
  if (v[nearest] * outward < 0.0)
    v[nearest] = 0.0;
}

template class RigidFooting<2>;
template class RigidFooting<3>;

}  // namespace mpm_lig::mpm
