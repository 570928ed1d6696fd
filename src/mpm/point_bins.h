#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "mpm/grid.h"

namespace mpm_lig::mpm {

//! Points binned in boxes at least `reach` wide over the grid, so that every point within
//! `reach` of a point lies in its box or a neighbouring one.
template <int D>
class PointBins {
 public:
  PointBins(const Grid<D>& grid, double reach) : grid_(grid) {
    for (int d = 0; d < D; ++d) {
      count_[d] = std::max(1L, static_cast<long>(std::floor(grid.size()[d] / reach)));
      side_[d] = grid.size()[d] / static_cast<double>(count_[d]);
    }
    long total = 1;
    for (int d = 0; d < D; ++d)
      total *= count_[d];
    members_.resize(static_cast<std::size_t>(total));
  }

  void add(std::size_t point, const typename Grid<D>::Vec& x) {
    members_[flat(index(x))].push_back(point);
  }

  //! The distinct boxes next to (and including) the one holding x; a periodic axis wraps.
  std::vector<std::size_t> around(const typename Grid<D>::Vec& x) const {
    const std::array<long, D> centre = index(x);
    std::vector<std::size_t> boxes;
    std::array<int, D> offset;
    offset.fill(-1);
    while (true) {
      std::array<long, D> at{};
      bool inside = true;
      for (int d = 0; d < D; ++d) {
        at[d] = centre[d] + offset[d];
        if (grid_.periodic(d))
          at[d] = ((at[d] % count_[d]) + count_[d]) % count_[d];
        else if (at[d] < 0 || at[d] >= count_[d])
          inside = false;
      }
      if (inside)
        boxes.push_back(flat(at));
      int d = 0;
      while (d < D && ++offset[d] > 1)
        offset[d++] = -1;
      if (d == D)
        break;
    }
    std::sort(boxes.begin(), boxes.end());
    boxes.erase(std::unique(boxes.begin(), boxes.end()), boxes.end());
    return boxes;
  }

  const std::vector<std::size_t>& members(std::size_t box) const { return members_[box]; }

 private:
  std::array<long, D> index(const typename Grid<D>::Vec& x) const {
    std::array<long, D> at{};
    for (int d = 0; d < D; ++d) {
      const double xi = (x[d] - grid_.origin()[d]) / side_[d];
      at[d] = std::clamp(static_cast<long>(std::floor(xi)), 0L, count_[d] - 1);
    }
    return at;
  }
  std::size_t flat(const std::array<long, D>& at) const {
    std::size_t id = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      id += static_cast<std::size_t>(at[d]) * stride;
      stride *= static_cast<std::size_t>(count_[d]);
    }
    return id;
  }

  const Grid<D>& grid_;
  std::array<long, D> count_{};
  std::array<double, D> side_{};
  std::vector<std::vector<std::size_t>> members_;
};

//! x_q − x_p, the nearest image along periodic axes.
template <int D>
typename Grid<D>::Vec separation(const Grid<D>& grid, const typename Grid<D>::Vec& from,
                                 const typename Grid<D>::Vec& to) {
  typename Grid<D>::Vec dx = to - from;
  for (int d = 0; d < D; ++d) {
    if (grid.periodic(d))
      dx[d] -= grid.size()[d] * std::round(dx[d] / grid.size()[d]);
  }
  return dx;
}

}  // namespace mpm_lig::mpm
