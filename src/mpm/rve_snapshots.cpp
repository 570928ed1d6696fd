#include "mpm/rve_snapshots.h"

#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace mpm_lig::mpm {
namespace {

std::string numbered(const char* format, long n) {
  char name[32];
  std::snprintf(name, sizeof name, format, n);
  return name;
}

//! The point with a microstructure nearest to `x` in the reference configuration.
template <int D>
std::size_t nearest_dem_point(const Solver<D>& solver, const std::vector<double>& x) {
  const Particles<D>& p = solver.particles();
  typename Particles<D>::Vec target;
  for (int d = 0; d < D; ++d)
    target[d] = x[d];
  std::size_t best = p.size();
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!materials::has_snapshots(*solver.materials()[p.material[k]]))
      continue;
    const double distance = (p.reference[k] - target).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = k;
    }
  }
  if (best == p.size())
    throw std::runtime_error("output.rve_snapshots: no material point has an RVE");
  return best;
}

}  // namespace

template <int D>
RveSnapshots<D>::RveSnapshots(const RveSnapshotOutput& spec, const Solver<D>& solver,
                              const std::string& directory, long total_steps)
    : directory_(directory), every_(spec.every), total_steps_(total_steps) {
  for (const std::vector<double>& x : spec.at)
    points_.push_back(nearest_dem_point(solver, x));
}

template <int D>
void RveSnapshots<D>::after_step(Solver<D>& solver) {
  const long step = solver.steps();
  if (points_.empty())
    return;
  if (step == 0 || step == total_steps_ || (every_ > 0 && step % every_ == 0))
    write(solver);
}

template <int D>
void RveSnapshots<D>::write(Solver<D>& solver) {
  const Particles<D>& p = solver.particles();
  for (const std::size_t k : points_) {
    const std::filesystem::path folder =
        std::filesystem::path(directory_) / "snapshots" / numbered("point_%06ld", long(k));
    std::filesystem::create_directories(folder);
    const std::string prefix = (folder / numbered("rve_%06ld", solver.steps())).string();
    // Only points of materials with snapshots are chosen (nearest_dem_point).
    materials::snapshots_of(*solver.materials()[p.material[k]])
        ->write_snapshot(p.material_point[k], prefix);
  }
}

template class RveSnapshots<2>;
template class RveSnapshots<3>;

}  // namespace mpm_lig::mpm
