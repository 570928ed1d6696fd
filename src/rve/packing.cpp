#include "rve/packing.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace mpm_lig::rve {
namespace {

double draw_radius(const RadiusSpec& r, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double u = unit(rng);
  if (r.radii.empty())
    return r.min + u * (r.max - r.min);
  // Invert the piecewise-linear cumulative distribution.
  for (std::size_t i = 1; i < r.radii.size(); ++i) {
    if (u <= r.cumulative[i] && r.cumulative[i] > r.cumulative[i - 1]) {
      const double t = (u - r.cumulative[i - 1]) / (r.cumulative[i] - r.cumulative[i - 1]);
      return r.radii[i - 1] + t * (r.radii[i] - r.radii[i - 1]);
    }
  }
  return r.radii.back();
}

//! Uniform grid of buckets over the periodic cell, for overlap queries in O(1).
class Buckets {
 public:
  Buckets(double length, double reach, int dimension)
      : n_(std::max(1, static_cast<int>(length / reach))),
        dimension_(dimension),
        length_(length),
        cells_(static_cast<std::size_t>(std::pow(n_, dimension))) {}

  void add(const Vec3& x, std::size_t id) { cells_[index(coords(x))].push_back(id); }

  //! True if a grain at x with radius r overlaps any grain already placed.
  bool overlaps(const Vec3& x, double r, const Packing& p) const {
    const auto c = coords(x);
    const int zr = dimension_ == 3 ? 1 : 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -zr; dz <= zr; ++dz) {
          const std::array<int, 3> k = {c[0] + dx, c[1] + dy, c[2] + dz};
          for (std::size_t id : cells_[index(k)]) {
            Vec3 d = p.centres[id] - x;
            for (int a = 0; a < dimension_; ++a)
              d[a] -= length_ * std::round(d[a] / length_);
            const double reach = p.radii[id] + r;
            if (d.squaredNorm() < reach * reach)
              return true;
          }
        }
    return false;
  }

 private:
  std::array<int, 3> coords(const Vec3& x) const {
    std::array<int, 3> c{0, 0, 0};
    for (int a = 0; a < dimension_; ++a)
      c[a] = std::min(n_ - 1, static_cast<int>(x[a] / length_ * n_));
    return c;
  }
  std::size_t index(std::array<int, 3> c) const {
    std::size_t i = 0;
    for (int a = dimension_ - 1; a >= 0; --a)
      i = i * n_ + static_cast<std::size_t>(((c[a] % n_) + n_) % n_);
    return i;
  }

  int n_;
  int dimension_;
  double length_;
  std::vector<std::vector<std::size_t>> cells_;
};

}  // namespace

double solid_measure(const std::vector<double>& radii, int dimension) {
  double sum = 0.0;
  for (double r : radii)
    sum += dimension == 2 ? kPi * r * r : 4.0 / 3.0 * kPi * r * r * r;
  return sum;
}

Packing generate_packing(const RveSpec& spec) {
  std::mt19937_64 rng(spec.seed);
  Packing p;
  for (long i = 0; i < spec.grains; ++i)
    p.radii.push_back(draw_radius(spec.radius, rng));
  // Large grains first: they are the hardest to place.
  std::sort(p.radii.begin(), p.radii.end(), std::greater<double>());
  const int dim = spec.dimension;
  const double solid = solid_measure(p.radii, dim);
  p.cell_length = std::pow(solid / spec.preparation.initial_solid_fraction, 1.0 / dim);

  Buckets buckets(p.cell_length, 2.0 * p.radii.front(), dim);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int kAttempts = 100000;
  for (double r : p.radii) {
    bool placed = false;
    for (int attempt = 0; attempt < kAttempts && !placed; ++attempt) {
      Vec3 x(unit(rng) * p.cell_length, unit(rng) * p.cell_length,
             dim == 3 ? unit(rng) * p.cell_length : 0.0);
      if (!buckets.overlaps(x, r, p)) {
        buckets.add(x, p.centres.size());
        p.centres.push_back(x);
        placed = true;
      }
    }
    if (!placed)
      throw std::runtime_error("could not place grain " + std::to_string(p.centres.size() + 1) +
                               " of " + std::to_string(spec.grains) +
                               " without overlap: lower preparation.initial_solid_fraction");
  }
  return p;
}

}  // namespace mpm_lig::rve
