#include "rve/observables.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpm_lig::rve {

double Observables::kinetic_ratio() const {
  if (kinetic_energy == 0.0)
    return 0.0;
  return elastic_energy > 0.0 ? kinetic_energy / elastic_energy
                              : std::numeric_limits<double>::infinity();
}

double Observables::flow_ratio() const {
  if (kinetic_energy == 0.0)
    return 0.0;
  return flow_energy > 0.0 ? kinetic_energy / flow_energy : std::numeric_limits<double>::infinity();
}

GrainState gather_grains(dem::Engine& engine) {
  auto vec3 = [&](const char* name) {
    const std::vector<double> flat = engine.gather_atoms(name, 3);
    std::vector<Vec3> out(flat.size() / 3);
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
    return out;
  };
  GrainState g;
  g.x = vec3("x");
  g.v = vec3("v");
  g.omega = vec3("omega");
  g.radius = engine.gather_atoms("radius", 1);
  g.mass = engine.gather_atoms("rmass", 1);
  return g;
}

Mat3 contact_stress(const std::vector<dem::Contact>& contacts, double volume) {
  Mat3 sum = Mat3::Zero();
  for (const auto& c : contacts)
    sum += c.branch * c.force.transpose();
  // Not symmetrised: grains out of rotational equilibrium make it slightly asymmetric, and the
  // engines report the upper components (xy = Σ r_x f_y, as in their virial).
  return sum / volume;
}

void add_grain_measures(const GrainState& grains, const std::vector<dem::Contact>& contacts,
                        const Mat3& streaming, const Vec3& origin, Observables& out) {
  out.grains = static_cast<long>(grains.x.size());
  out.contacts = 0;
  out.elastic_energy = 0.0;
  out.max_overlap_ratio = 0.0;
  std::vector<char> loaded(grains.x.size(), 0);
  for (const auto& c : contacts) {
    const double distance = c.branch.norm();
    const double fn = std::abs(c.force.dot(c.branch)) / distance;
    if (fn <= 0.0)
      continue;
    ++out.contacts;
    loaded[c.id_i - 1] = loaded[c.id_j - 1] = 1;
    const double overlap =
        grains.radius[c.id_i - 1] + grains.radius[c.id_j - 1] - distance;  // ids start at 1
    if (overlap > 0.0) {
      out.elastic_energy += 0.4 * fn * overlap;
      out.mean_overlap_strain += overlap / distance;
      const double smaller = std::min(grains.radius[c.id_i - 1], grains.radius[c.id_j - 1]);
      out.max_overlap_ratio = std::max(out.max_overlap_ratio, overlap / smaller);
    }
  }
  if (out.contacts > 0)
    out.mean_overlap_strain /= static_cast<double>(out.contacts);
  out.coordination_number = out.grains > 0 ? 2.0 * out.contacts / out.grains : 0.0;
  add_motion_measures(grains, loaded, streaming, origin, out);
}

void add_health_measures(const GrainState& grains, const std::vector<dem::Overlap>& overlaps,
                         const Mat3& streaming, const Vec3& origin, Observables& out) {
  out.grains = static_cast<long>(grains.x.size());
  out.max_overlap_ratio = 0.0;
  std::vector<char> loaded(grains.x.size(), 0);
  for (const auto& o : overlaps) {
    loaded[o.id_i - 1] = loaded[o.id_j - 1] = 1;  // ids start at 1
    out.max_overlap_ratio = std::max(out.max_overlap_ratio, o.ratio);
  }
  add_motion_measures(grains, loaded, streaming, origin, out);
}

void add_motion_measures(const GrainState& grains, const std::vector<char>& loaded,
                         const Mat3& streaming, const Vec3& origin, Observables& out) {
  // Fluctuations about the affine field and about the mean motion (a uniform drift of a
  // periodic packing is no deformation).
  std::vector<Vec3> fluctuation(grains.x.size());
  Vec3 momentum = Vec3::Zero();
  double mass = 0.0;
  for (std::size_t i = 0; i < grains.x.size(); ++i) {
    fluctuation[i] = grains.v[i] - streaming * (grains.x[i] - origin);
    momentum += grains.mass[i] * fluctuation[i];
    mass += grains.mass[i];
  }
  const Vec3 drift = mass > 0.0 ? Vec3(momentum / mass) : Vec3::Zero();
  out.kinetic_energy = 0.0;
  out.max_speed_ratio = 0.0;
  out.flow_energy = 0.0;
  const double rate = streaming.norm();
  for (std::size_t i = 0; i < grains.x.size(); ++i) {
    // Every grain, rattlers too: a grain crossing a large part of its radius in one step is
    // numerical whether or not it touches another.
    const double speed =
        (fluctuation[i] - drift).norm() + grains.omega[i].norm() * grains.radius[i];
    out.max_speed_ratio = std::max(out.max_speed_ratio, speed / grains.radius[i]);
    out.flow_energy += 0.5 * grains.mass[i] * std::pow(2.0 * rate * grains.radius[i], 2);
    // Rattlers (no contact) fly freely and undamped without touching the stress: leave
    // them out, or a packing at rest never looks at rest.
    if (!loaded[i])
      continue;
    const double inertia = 0.4 * grains.mass[i] * grains.radius[i] * grains.radius[i];
    out.kinetic_energy += 0.5 * grains.mass[i] * (fluctuation[i] - drift).squaredNorm() +
                          0.5 * inertia * grains.omega[i].squaredNorm();
  }
}

}  // namespace mpm_lig::rve
