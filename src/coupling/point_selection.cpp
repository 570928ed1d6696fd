#include "coupling/point_selection.h"

namespace mpm_lig::coupling {

void PointSelection::start(std::size_t points, int dimension, double stress_floor,
                           const std::vector<Packing>& packings, const PackingOrder& order) {
  quiet_.start(points, quiet_spec_, dimension, stress_floor, continuum_start_spec_);
  flow_.start(points, flow_spec_, dimension, stress_floor);
  for (std::size_t point = 0; point < points; ++point) {
    const Packing& packing = packings[order.of(point)];
    quiet_.set_packing(point, packing.stress, packing.wave_modulus, packing.lateral_modulus);
    flow_.set_packing(
        point, mean_pressure(packing.stress, dimension),
        packing_moduli(packing.wave_modulus, packing.lateral_modulus, dimension).bulk);
  }
}

DemBatch PointSelection::select(std::size_t points, const materials::MaterialStep& step) {
  DemBatch batch;
  batch.index.assign(points, -1);
  for (std::size_t i = 0; i < step.points.size(); ++i)
    batch.index[step.points[i]] = static_cast<long>(i);
  batch.increments = step.dF;  // a predicted point's entry is only booked (zero steps)
  if (!quiet_.enabled() && !flow_.enabled())
    return batch;
  for (std::size_t i = 0; i < step.points.size(); ++i) {
    const std::size_t p = step.points[i];
    if (flow_.enabled() && flow_.flowing(p)) {
      if (flow_.accumulate(p, step.dF[i]))
        batch.increments[i] = flow_.catch_up(p);
      else
        batch.index[p] = -1;
    } else if (quiet_.enabled()) {
      if (quiet_.accumulate(p, step.dF[i]))
        batch.increments[i] = quiet_.pending(p);
      else
        batch.index[p] = -1;
    }
  }
  return batch;
}

void PointSelection::settle(const std::vector<std::size_t>& points, const DemBatch& batch,
                            std::vector<Mat3>& stress) {
  if (!quiet_.enabled() && !flow_.enabled())
    return;
  for (const std::size_t p : points) {
    if (!batch.runs(p)) {
      stress[p] = flow_.enabled() && flow_.flowing(p) ? flow_.predicted(p) : quiet_.predicted(p);
      continue;
    }
    // A continuum point's switch runs its whole deformation at once: no window of a flow.
    const bool switches = quiet_.enabled() && quiet_.is_continuum(p);
    if (quiet_.enabled())
      quiet_.after_dem(p, stress[p]);
    if (flow_.enabled() && !switches)
      flow_.after_dem(p, batch.increment(p), stress[p]);
  }
}

}  // namespace mpm_lig::coupling
