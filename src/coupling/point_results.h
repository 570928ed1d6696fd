#pragma once

#include <cstddef>
#include <vector>

#include "core/tensor.h"
#include "coupling/point_selection.h"
#include "coupling/rve_layout.h"

namespace mpm_lig::coupling {

//! Every point's latest DEM results, the same on every rank (gathered after each update).
struct PointResults {
  std::vector<Mat3> stress;          //!< every point's last stress
  std::vector<double> substeps;      //!< every point's last DEM step count
  std::vector<double> dem_pressure;  //!< every RVE's mean stress as it knows it (Rve::State)
  std::vector<double> net_shear;     //!< every RVE's net shear strain (Rve::net_shear)

  //! `points` points at zero: stresses, steps, and mean stresses not measured yet.
  void start(std::size_t points);
};

//! Doubles per owned point in the exchange: its stress (9), DEM steps, net shear and seconds.
constexpr int kResultWidth = 12;
//! Append one owned point's row to `rows`.
void append_result(std::vector<double>& rows, const Mat3& stress, double steps, double net_shear,
                   double seconds);

//! Collective over the layout's ranks, one MPI_Allgatherv: the owners' rows (`owned`, in the
//! order of layout.owned()) to every rank, in point order. Sets every point's stress and steps
//! and net shear in `results`, and the mean stress of the points that ran DEM (`batch`), as
//! Rve::stress() does; returns every point's seconds.
std::vector<double> gather_results(const RveLayout& layout, const std::vector<double>& owned,
                                   const DemBatch& batch, int dimension, PointResults& results);

}  // namespace mpm_lig::coupling
