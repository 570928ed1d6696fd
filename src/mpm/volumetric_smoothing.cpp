#include "mpm/volumetric_smoothing.h"

#include <algorithm>
#include <cmath>

namespace mpm_lig::mpm {
namespace {

//! Each point's cell (flat index) and each cell's volume, from the context's positions.
struct CellVolumes {
  std::vector<std::size_t> cell_of;
  std::vector<double> volume;
};

template <int D>
CellVolumes cell_volumes(const Particles<D>& particles, const Grid<D>& grid) {
  std::size_t cells = 1;
  for (int d = 0; d < D; ++d)
    cells *= grid.cells(d);
  CellVolumes out{std::vector<std::size_t>(particles.size()), std::vector<double>(cells, 0.0)};
  for (std::size_t p = 0; p < particles.size(); ++p) {
    std::size_t id = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      const double xi = (particles.position[p][d] - grid.origin()[d]) / grid.cell()[d];
      const long c = std::clamp(static_cast<long>(std::floor(xi)), 0L, grid.cells(d) - 1L);
      id += c * stride;
      stride *= grid.cells(d);
    }
    out.cell_of[p] = id;
    out.volume[id] += particles.volume[p];
  }
  return out;
}

}  // namespace

template <int D>
void VolumetricSmoothing<D>::apply(const KinematicsContext<D>& context,
                                   std::vector<Mat3>& increments) const {
  const Particles<D>& particles = context.particles;
  const CellVolumes cells = cell_volumes(particles, context.grid);
  std::vector<double> weighted(cells.volume.size(), 0.0);
  for (std::size_t p = 0; p < particles.size(); ++p)
    weighted[cells.cell_of[p]] += particles.volume[p] * increments[p].determinant();
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const double j_bar = weighted[cells.cell_of[p]] / cells.volume[cells.cell_of[p]];
    const double j = increments[p].determinant();
    increments[p].template topLeftCorner<D, D>() *= std::pow(j_bar / j, 1.0 / D);
  }
}

template <int D>
void VolumetricSmoothing<D>::pull_back(
    const KinematicsContext<D>& context,
    std::vector<typename KinematicsOperator<D>::Tensor>& tensors) const {
  const Particles<D>& particles = context.particles;
  const CellVolumes cells = cell_volumes(particles, context.grid);
  std::vector<double> mean_part(cells.volume.size(), 0.0);  // Σ_p tr S_p / D over the cell
  for (std::size_t p = 0; p < particles.size(); ++p)
    mean_part[cells.cell_of[p]] += tensors[p].trace() / D;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const std::size_t c = cells.cell_of[p];
    const double own = tensors[p].trace() / D;
    const double shared = particles.volume[p] / cells.volume[c] * mean_part[c];
    tensors[p].diagonal().array() += shared - own;
  }
}

template class VolumetricSmoothing<2>;
template class VolumetricSmoothing<3>;

}  // namespace mpm_lig::mpm
