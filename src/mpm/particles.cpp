#include "mpm/particles.h"

#include <cmath>

#include "mpm/case_size.h"

namespace mpm_lig::mpm {
namespace {

template <int D>
void fill_body(const MpmCase& c, MaterialSet& materials, int body_index, Particles<D>& p) {
  using Vec = typename Particles<D>::Vec;
  const Body& body = c.bodies[body_index];
  materials::Material& material = *materials[body.material];
  std::array<long, D> count{};
  std::array<std::vector<double>, D> coordinates;
  Vec spacing, cell;
  long total = 1;
  const std::vector<double> along = points_along_axes(c, body);
  for (int d = 0; d < D; ++d) {
    cell[d] = c.size[d] / c.cells[d];
    count[d] = static_cast<long>(along[d]);
    spacing[d] = (body.box.max[d] - body.box.min[d]) / count[d];
    coordinates[d] = point_coordinates(c, body, d);
    total *= count[d];
  }
  const double volume = spacing.prod();
  const std::size_t first = material.add_points(static_cast<std::size_t>(total));
  for (long k = 0; k < total; ++k) {
    Vec x;
    long rest = k;
    for (int d = 0; d < D; ++d) {
      x[d] = coordinates[d][rest % count[d]];
      rest /= count[d];
    }
    Vec v = Eigen::Map<const Vec>(body.velocity.data());
    if (body.has_profile) {
      const double s =
          std::sin(0.5 * kPi * (x[body.profile_axis] - body.profile_start) / body.profile_length);
      v += s * Eigen::Map<const Vec>(body.profile_amplitude.data());
    }
    p.position.push_back(x);
    p.reference.push_back(x);
    p.velocity.push_back(v);
    p.half_length.push_back(0.5 * spacing.cwiseQuotient(cell));
    p.external_force.push_back(Vec::Zero());
    p.mass.push_back(material.density() * volume);
    p.volume.push_back(volume);
    p.volume0.push_back(volume);
    p.deformation.push_back(Mat3::Identity());
    const std::size_t point = first + static_cast<std::size_t>(k);
    if (body.initial_stress)
      material.set_stress(point, *body.initial_stress);
    p.stress.push_back(body.initial_stress ? *body.initial_stress : material.initial_stress(point));
    p.material.push_back(body.material);
    p.material_point.push_back(first + static_cast<std::size_t>(k));
    p.body.push_back(body_index);
  }
}

}  // namespace

template <int D>
Particles<D> generate_particles(const MpmCase& c, MaterialSet& materials) {
  Particles<D> p;
  for (int b = 0; b < static_cast<int>(c.bodies.size()); ++b)
    fill_body<D>(c, materials, b, p);
  return p;
}

template Particles<2> generate_particles<2>(const MpmCase&, MaterialSet&);
template Particles<3> generate_particles<3>(const MpmCase&, MaterialSet&);

}  // namespace mpm_lig::mpm
