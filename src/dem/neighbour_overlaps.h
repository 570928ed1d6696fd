#pragma once
// Near pairs from the pair style's neighbour list, shared by both engine modules. Internal to
// src/dem.

#include <vector>

#include "lmptype.h"  // the engine's own NEIGHMASK (include path set per module)

namespace mpm_lig::dem::detail {

//! Rows (id_i, id_j, radius_i, radius_j) of this rank's neighbour pairs closer than
//! (1 + kNearMargin) (r_i + r_j) in the engine's own images: the ghost images of a periodic
//! pair may still sit in the previous step's cell after a run under `fix deform`, so the exact
//! test is left to LibraryEngine::overlaps_of (minimum image in the current box).
//! `element(ii, i, count, neighbours)` gives list element ii: atom i and its neighbours.
template <class Tag, class Element>
std::vector<double> near_pair_rows(int elements, Element element, double** x, const double* radius,
                                   const Tag* tag) {
  constexpr double kNearMargin = 0.01;
  std::vector<double> rows;
  for (int ii = 0; ii < elements; ++ii) {
    int i = 0, count = 0;
    int* neighbours = nullptr;
    element(ii, i, count, neighbours);
    for (int jj = 0; jj < count; ++jj) {
      const int j = neighbours[jj] & NEIGHMASK;
      const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
      const double reach = (1.0 + kNearMargin) * (radius[i] + radius[j]);
      if (dx * dx + dy * dy + dz * dz < reach * reach)
        rows.insert(rows.end(), {static_cast<double>(tag[i]), static_cast<double>(tag[j]),
                                 radius[i], radius[j]});
    }
  }
  return rows;
}

}  // namespace mpm_lig::dem::detail
