#include "mpm/grid.h"

namespace mpm_lig::mpm {

template <int D>
Grid<D>::Grid(const Vec& origin, const Vec& size, const std::array<int, D>& cells,
              const std::array<bool, D>& periodic)
    : origin_(origin), size_(size), cells_(cells), periodic_(periodic) {
  long count = 1;
  for (int d = 0; d < D; ++d) {
    cell_[d] = size[d] / cells[d];
    stride_[d] = count;
    count *= cells[d] + 1;
  }
  mass.assign(count, 0.0);
  momentum.assign(count, Vec::Zero());
  force.assign(count, Vec::Zero());
  velocity.assign(count, Vec::Zero());
  velocity_new.assign(count, Vec::Zero());
  damping.assign(count, Vec::Zero());
}

template <int D>
long Grid<D>::node_id(const std::array<long, D>& index) const {
  long id = 0;
  for (int d = 0; d < D; ++d) {
    if (index[d] < 0 || index[d] > cells_[d])
      return -1;
    id += index[d] * stride_[d];
  }
  return id;
}

template <int D>
typename Grid<D>::Index Grid<D>::node_index(long id) const {
  Index index;
  for (int d = D - 1; d >= 0; --d) {
    index[d] = id / stride_[d];
    id -= index[d] * stride_[d];
  }
  return index;
}

template <int D>
typename Grid<D>::Vec Grid<D>::node_position(long id) const {
  return origin_ + node_index(id).template cast<double>().cwiseProduct(cell_);
}

template <int D>
void Grid<D>::reset() {
  std::fill(mass.begin(), mass.end(), 0.0);
  std::fill(momentum.begin(), momentum.end(), Vec::Zero());
  std::fill(force.begin(), force.end(), Vec::Zero());
}

template class Grid<2>;
template class Grid<3>;

}  // namespace mpm_lig::mpm
