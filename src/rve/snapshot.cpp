#include "rve/snapshot.h"

#include "io/vtk_snapshot.h"
#include "rve/observables.h"

namespace mpm_lig::rve {

void write_snapshot(Rve& rve, const std::string& prefix, bool writer) {
  const GrainState grains = gather_grains(rve.engine());
  const std::vector<dem::Contact> contacts = rve.engine().contacts();
  Vec3 lo = rve.engine().box().lo;
  if (rve.spec().dimension == 2)
    lo.z() = 0.0;  // discs stay in the plane z = 0
  if (!writer)
    return;
  const Mat3& q = rve.rotation();
  std::vector<Vec3> x, v;
  for (std::size_t i = 0; i < grains.x.size(); ++i) {
    x.push_back(q * (grains.x[i] - lo));
    v.push_back(q * grains.v[i]);
  }
  io::write_vtk_grains(prefix + "_grains.vtk", x, grains.radius, v);

  std::vector<Vec3> starts, ends;
  std::vector<double> force;
  for (const auto& c : contacts) {
    const double f = c.force.norm();
    if (f <= 0.0)
      continue;
    starts.push_back(x[c.id_i - 1]);
    ends.push_back(x[c.id_i - 1] + q * c.branch);
    force.push_back(f);
  }
  io::write_vtk_lines(prefix + "_contacts.vtk", starts, ends, "force", force);

  // The cell: 12 edges of the parallelepiped spanned by the box vectors.
  const Mat3 h = q * rve.box_matrix();
  std::vector<Vec3> a, b;
  std::vector<double> edge;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int k = 0; k < 4; ++k) {
      const Vec3 base = double(k & 1) * h.col(u) + double((k >> 1) & 1) * h.col(w);
      a.push_back(base);
      b.push_back(base + h.col(axis));
      edge.push_back(axis);
    }
  }
  io::write_vtk_lines(prefix + "_cell.vtk", a, b, "edge_direction", edge);
}

}  // namespace mpm_lig::rve
