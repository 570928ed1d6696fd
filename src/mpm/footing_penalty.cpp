#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/tensor.h"
#include "mpm/footing.h"

namespace mpm_lig::mpm {

namespace {

constexpr double kNoAnchor = std::numeric_limits<double>::quiet_NaN();

}  // namespace

// Coulomb's limit on the rough base's hold: where the spring's tangential force would pass
// tan δ × the normal force, the anchor follows the point so that it sits on the limit
// (the point slides along the base).
template <int D>
void RigidFooting<D>::slide_past_friction_limit(Vec& f, const Vec& x, Vec& anchor) const {
  constexpr int up = D - 1;
  if (spec_.interface_friction_deg >= 90.0)
    return;
  const double limit = std::tan(spec_.interface_friction_deg * kDegree) * std::abs(f[up]);
  const double tangential = f.head(up).norm();
  if (tangential <= limit)
    return;
  const double keep = limit / tangential;
  for (int d = 0; d < up; ++d) {
    f[d] *= keep;
    anchor[d] = x[d] - keep * (x[d] - anchor[d]);
  }
}

template <int D>
void RigidFooting<D>::press(Particles<D>& particles, const Vec& cell, double modulus) {
  constexpr int up = D - 1;
  const double stiffness = spec_.penalty_stiffness * modulus;
  const double base_now = base();
  if (anchors_.size() != particles.size())
    anchors_.assign(particles.size(), Vec::Constant(kNoAnchor));
  Vec reaction = Vec::Zero();
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const Vec& x = particles.position[p];
    const Vec half = particles.half_length[p].cwiseProduct(cell);
    // How far the point's box reaches into the footing through its base, how much of it
    // lies under the footprint along each horizontal axis, and the shortest way out through
    // a side face.
    const double through_base = x[up] + half[up] - base_now;
    std::array<double, D> overlap{};
    double under = 1.0;
    double through_side = std::numeric_limits<double>::max();
    int side = 0;
    double outward = 1.0;
    for (int d = 0; d < up; ++d) {
      const double lo = pressed_lo_[d], hi = pressed_hi_[d];
      overlap[d] = std::max(0.0, std::min(x[d] + half[d], hi) - std::max(x[d] - half[d], lo));
      under *= overlap[d];
      const double out_lo = x[d] + half[d] - lo, out_hi = hi - (x[d] - half[d]);
      if (std::min(out_lo, out_hi) < through_side) {
        through_side = std::min(out_lo, out_hi);
        side = d;
        outward = out_hi <= out_lo ? 1.0 : -1.0;
      }
    }
    Vec& anchor = anchors_[p];
    if (through_base <= 0.0 || under <= 0.0) {
      anchor[0] = kNoAnchor;
      continue;
    }
    // A pressure of stiffness x overlap / cell on the face of the box it pushes.
    Vec f = Vec::Zero();
    if (through_base <= through_side) {
      f[up] = -stiffness * through_base / cell[up] * under;
      if (spec_.rough) {
        if (std::isnan(anchor[0]))
          anchor = x;
        for (int d = 0; d < up; ++d)
          f[d] = -stiffness * (x[d] - anchor[d]) / cell[up] * under;
        slide_past_friction_limit(f, x, anchor);
      }
    } else {
      anchor[0] = kNoAnchor;
      double face = std::min(through_base, 2.0 * half[up]);
      for (int d = 0; d < up; ++d)
        face *= d == side ? 1.0 : overlap[d];
      f[side] = outward * stiffness * through_side / cell[side] * face;
    }
    particles.external_force[p] += f;
    reaction += f;
  }
  load_ = -reaction[up];
  reaction_ = reaction;
}

template void RigidFooting<2>::press(Particles<2>&, const Eigen::Vector2d&, double);
template void RigidFooting<3>::press(Particles<3>&, const Eigen::Vector3d&, double);

}  // namespace mpm_lig::mpm
