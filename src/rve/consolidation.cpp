#include "rve/consolidation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mpm_lig::rve {
namespace {

//! Steps per servo cycle: short against the time a stress wave needs to cross the cell.
constexpr int kChunk = 100;
//! Compaction stops at the target void ratio once the pressure is this close (relative) to its
//! target: the re-consolidation with the real friction then changes the void ratio little.
constexpr double kNearTarget = 0.05;
//! A relaxed packing: kinetic energy this small against the elastic energy.
constexpr double kAtRest = 2e-3;

//! Fastest servo strain rate: inertial number 5e-3 at the target pressure unless asked.
double max_strain_rate(const RveSpec& spec, double pressure) {
  if (spec.preparation.max_strain_rate > 0.0)
    return spec.preparation.max_strain_rate;
  return 5e-3 / (2.0 * spec.radius.mean() * std::sqrt(spec.density / pressure));
}

}  // namespace

Observables servo_isotropic(Rve& rve, double pressure, double tolerance, long& steps_left,
                            double stop_void_ratio) {
  const RveSpec& spec = rve.spec();
  const int dim = spec.dimension;
  const double max_step = max_strain_rate(spec, pressure) * kChunk * spec.time_step;
  Observables now = rve.observe();
  int settled = 0;
  while (steps_left > 0) {
    const double p = mean_pressure(now.stress, dim);
    // Each axis is driven towards the target on its own, so that the normal stresses end up
    // equal (not only their mean); shear stresses of the fabric are not controlled.
    Mat3 dF = Mat3::Identity();
    for (int i = 0; i < dim; ++i) {
      double strain = -max_step;  // loose: close the gaps at full speed
      if (p > 0.2 * pressure && now.mean_overlap_strain > 0.0) {
        // Affine Hertz stiffness dp/dε = 1.5 p / (δ/d): an upper bound of the packing's, so
        // the correction never overshoots (it converges geometrically instead).
        const double stiffness = 1.5 * p / now.mean_overlap_strain;
        strain = std::clamp(-0.5 * (pressure + now.stress(i, i)) / stiffness, -max_step, max_step);
      }
      dF(i, i) = 1.0 + strain;
    }
    rve.deform(dF, kChunk);
    steps_left -= kChunk;
    now = rve.observe();
    const double p_new = mean_pressure(now.stress, dim);
    if (stop_void_ratio > 0.0 && now.void_ratio <= stop_void_ratio &&
        std::abs(p_new - pressure) <= kNearTarget * pressure)
      return now;
    const bool on_target = std::abs(p_new - pressure) <= tolerance * pressure;
    settled = on_target && now.kinetic_ratio() < kAtRest ? settled + 1 : 0;
    if (settled >= 3)
      return now;
  }
  throw std::runtime_error(rve.label() + ": isotropic servo to " + std::to_string(pressure) +
                           " Pa did not settle within the step budget (" + spec.path +
                           ".preparation.max_steps)");
}

ConsolidationResult consolidate(Rve& rve) {
  const RveSpec& spec = rve.spec();
  const PreparationSpec& prep = spec.preparation;
  ConsolidationResult result;
  long steps_left = prep.max_steps;
  double friction = spec.contact.friction;
  result.friction_used = friction;
  // Lower friction lets grains slide into a denser packing; halve it until the target void
  // ratio is reached (or friction is gone), stopping the compaction as soon as the void ratio
  // crosses the target, then consolidate with the real friction.
  result.final = servo_isotropic(rve, prep.confining_pressure, prep.tolerance, steps_left);
  if (prep.target_void_ratio) {
    while (result.final.void_ratio > *prep.target_void_ratio && friction > 0.0) {
      friction = friction > 1e-3 ? 0.5 * friction : 0.0;
      rve.set_friction(friction);
      result.final = servo_isotropic(rve, prep.confining_pressure, prep.tolerance, steps_left,
                                     *prep.target_void_ratio);
    }
    result.friction_used = friction;
    result.void_ratio_reached = result.final.void_ratio <= *prep.target_void_ratio;
    if (friction != spec.contact.friction) {
      rve.set_friction(spec.contact.friction);
      result.final = servo_isotropic(rve, prep.confining_pressure, prep.tolerance, steps_left);
    }
  }
  result.steps = prep.max_steps - steps_left;
  return result;
}

}  // namespace mpm_lig::rve
