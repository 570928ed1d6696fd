#pragma once

#include "rve/observables.h"
#include "rve/rve.h"

namespace mpm_lig::rve {

//! How a consolidation went.
struct ConsolidationResult {
  Observables final;                  //!< state at the end (relaxed, at the target pressure)
  double friction_used = 0;           //!< lowest friction used while compacting
  long steps = 0;                     //!< DEM steps spent
  bool void_ratio_reached = true;     //!< within preparation.void_ratio_tolerance of the target
  double void_ratio_error = 0.0;      //!< reached minus target void ratio
  double compacted_void_ratio = 0.0;  //!< at the end of the last low-friction stage
};

//! Isotropic servo compression of a fresh packing to `spec.preparation.confining_pressure`
//! (within its tolerance, and at rest), optionally towards a target void ratio by compacting
//! with lowered friction first. Throws std::runtime_error naming the RVE if the step budget
//! runs out.
ConsolidationResult consolidate(Rve& rve);

//! Throws std::runtime_error naming the RVE and the JSON path when a target void ratio was
//! asked and missed by more than preparation.void_ratio_tolerance.
void require_void_ratio(const Rve& rve, const ConsolidationResult& result);

//! Servo the RVE isotropically to mean stress `pressure` (within `tolerance`, relative) and
//! let it come to rest; returns the final state. With `stop_void_ratio` > 0 it returns as soon
//! as the void ratio is at or below it with the pressure within 5 % of the target (compaction).
Observables servo_isotropic(Rve& rve, double pressure, double tolerance, long& steps_left,
                            double stop_void_ratio = 0.0);

}  // namespace mpm_lig::rve
