#include "mpm/case_size.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/case_error.h"

namespace mpm_lig::mpm {
namespace {

//! Peak memory of one-step runs with fields written (docs/running.md §4), rounded up: 2D 5e5 and
//! 2e6 points took 0.59 and 2.28 GB; 3D 2.6e5 and 8.6e5 points took 0.52 and 1.71 GB.
constexpr double kBytesPerPoint[] = {0.0, 0.0, 1300.0, 2500.0};
constexpr double kBytesPerNode[] = {0.0, 0.0, 200.0, 300.0};

std::string count(double n) {
  std::ostringstream out;
  out << n;
  return out.str();
}

}  // namespace

std::vector<double> points_along_axes(const MpmCase& c, const Body& body) {
  std::vector<double> along(c.dimension);
  for (int d = 0; d < c.dimension; ++d) {
    const double cell = c.size[d] / c.cells[d];
    const double extent = body.box.max[d] - body.box.min[d];
    along[d] = std::max(1.0, std::round(extent / cell * body.points_per_cell));
  }
  return along;
}

std::vector<double> point_coordinates(const MpmCase& c, const Body& body, int axis) {
  const long count = static_cast<long>(points_along_axes(c, body)[axis]);
  const double spacing = (body.box.max[axis] - body.box.min[axis]) / count;
  std::vector<double> x(count);
  for (long i = 0; i < count; ++i)
    x[i] = body.box.min[axis] + (i + 0.5) * spacing;
  return x;
}

std::vector<double> points_per_material(const MpmCase& c) {
  std::vector<double> points(c.material_ids.size(), 0.0);
  for (const Body& body : c.bodies) {
    double n = 1.0;
    for (const double along : points_along_axes(c, body))
      n *= along;
    points[body.material] += n;
  }
  return points;
}

void add_mpm_memory(const MpmCase& c, const std::vector<double>& points, MemoryBudget& budget) {
  double nodes = 1.0;
  for (int d = 0; d < c.dimension; ++d)
    nodes *= c.cells[d] + 1.0;
  budget.add("mesh.cells", nodes * kBytesPerNode[c.dimension], count(nodes) + " grid nodes");
  double total = 0.0;
  for (const double n : points)
    total += n;
  budget.add("bodies", total * kBytesPerPoint[c.dimension], count(total) + " material points");
}

void check_step_counts(const MpmCase& c) {
  const std::string limit = count(kMaxSteps);
  if (c.end_steps > kMaxSteps)
    throw CaseError("analysis.end.steps", "more than " + limit + " steps");
  if (c.gravity_stage_steps > kMaxSteps)
    throw CaseError("analysis.gravity_stage.steps", "more than " + limit + " steps");
  if (c.fixed_time_step && c.end_time / c.time_step > kMaxSteps)
    throw CaseError("analysis.end.time", "takes " + count(c.end_time / c.time_step) + " steps of " +
                                             count(c.time_step) + " s: more than " + limit);
}

}  // namespace mpm_lig::mpm
