#include "mpm/volumetric_smoothing.h"

#include <algorithm>
#include <cmath>

namespace mpm_lig::mpm {

template <int D>
void VolumetricSmoothing<D>::apply(const KinematicsContext<D>& context,
                                   std::vector<Mat3>& increments) const {
  const Particles<D>& particles = context.particles;
  const Grid<D>& grid = context.grid;
  const std::size_t cells = [&] {
    std::size_t n = 1;
    for (int d = 0; d < D; ++d)
      n *= grid.cells(d);
    return n;
  }();
  std::vector<double> weight(cells, 0.0), weighted(cells, 0.0);
  std::vector<std::size_t> cell_of(particles.size());
  for (std::size_t p = 0; p < particles.size(); ++p) {
    std::size_t id = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      const double xi = (particles.position[p][d] - grid.origin()[d]) / grid.cell()[d];
      const long c = std::clamp(static_cast<long>(std::floor(xi)), 0L, grid.cells(d) - 1L);
      id += c * stride;
      stride *= grid.cells(d);
    }
    cell_of[p] = id;
    weight[id] += particles.volume[p];
    weighted[id] += particles.volume[p] * increments[p].determinant();
  }
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const double j_bar = weighted[cell_of[p]] / weight[cell_of[p]];
    const double j = increments[p].determinant();
    increments[p].template topLeftCorner<D, D>() *= std::pow(j_bar / j, 1.0 / D);
  }
}

template class VolumetricSmoothing<2>;
template class VolumetricSmoothing<3>;

}  // namespace mpm_lig::mpm
