#include "coupling/point_selection.h"

namespace mpm_lig::coupling {

void PointSelection::start(std::size_t points, int dimension, double stress_floor,
                           const std::vector<Packing>& packings) {
  quiet_.start(points, quiet_spec_, dimension, stress_floor, continuum_start_spec_);
  for (std::size_t point = 0; point < points; ++point) {
    const Packing& packing = packings[packing_of(point, packings.size())];
    quiet_.set_packing(point, packing.stress, packing.wave_modulus, packing.lateral_modulus);
  }
}

DemBatch PointSelection::select(std::size_t points, const materials::MaterialStep& step) {
  DemBatch batch;
  batch.index.assign(points, -1);
  for (std::size_t i = 0; i < step.points.size(); ++i)
    batch.index[step.points[i]] = static_cast<long>(i);
  batch.increments = step.dF;  // a quiet point's entry is only booked (zero steps)
  if (!quiet_.enabled())
    return batch;
  for (std::size_t i = 0; i < step.points.size(); ++i) {
    if (quiet_.accumulate(step.points[i], step.dF[i]))
      batch.increments[i] = quiet_.pending(step.points[i]);
    else
      batch.index[step.points[i]] = -1;
  }
  return batch;
}

void PointSelection::settle(const std::vector<std::size_t>& points, const DemBatch& batch,
                            std::vector<Mat3>& stress) {
  if (!quiet_.enabled())
    return;
  for (const std::size_t p : points) {
    if (batch.runs(p))
      quiet_.after_dem(p, stress[p]);
    else
      stress[p] = quiet_.predicted(p);
  }
}

}  // namespace mpm_lig::coupling
