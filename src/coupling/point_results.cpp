#include "coupling/point_results.h"

namespace mpm_lig::coupling {

void PointResults::start(std::size_t points) {
  stress.assign(points, Mat3::Zero());
  substeps.assign(points, 0.0);
  dem_pressure.assign(points, 0.0);  // a clone has not measured its stress yet
  net_shear.assign(points, 0.0);
}

void append_result(std::vector<double>& rows, const Mat3& stress, double steps, double net_shear,
                   double seconds) {
  rows.insert(rows.end(), stress.data(), stress.data() + 9);
  rows.push_back(steps);
  rows.push_back(net_shear);
  rows.push_back(seconds);
}

std::vector<double> gather_results(const RveLayout& layout, const std::vector<double>& owned,
                                   const DemBatch& batch, int dimension, PointResults& results) {
  const std::vector<double> all = layout.gather(owned, kResultWidth);
  const std::size_t points = results.stress.size();
  std::vector<double> seconds(points);
  for (std::size_t p = 0; p < points; ++p) {
    results.stress[p] = Eigen::Map<const Mat3>(&all[p * kResultWidth]);
    results.substeps[p] = all[p * kResultWidth + 9];
    results.net_shear[p] = all[p * kResultWidth + 10];
    seconds[p] = all[p * kResultWidth + 11];
    if (batch.runs(p))
      results.dem_pressure[p] = mean_pressure(results.stress[p], dimension);
  }
  return seconds;
}

}  // namespace mpm_lig::coupling
