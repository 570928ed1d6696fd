#pragma once

#include <cstddef>
#include <vector>

#include "core/tensor.h"
#include "coupling/packings.h"
#include "coupling/quiet_points.h"
#include "coupling/steady_flow.h"
#include "materials/material.h"

namespace mpm_lig::coupling {

//! One update of a dem_rve material as its RVEs see it: which points run DEM and under which
//! increment. The same on every rank (chosen from replicated data only).
struct DemBatch {
  //! Per point of the material: its entry in the MPM's batch, or -1 when it runs no DEM now
  //! (not in the batch, or quiet).
  std::vector<long> index;
  //! Per batch entry: the increment its RVE runs (a quiet point's MPM increment, booked only).
  std::vector<Mat3> increments;

  bool runs(std::size_t point) const { return index[point] >= 0; }
  //! The increment a point that runs() deforms its RVE by.
  const Mat3& increment(std::size_t point) const {
    return increments[static_cast<std::size_t>(index[point])];
  }
};

//! Which points run DEM at an update (docs/DESIGN.md §8): every point of the batch, or with
//! quiet points or a continuum start (QuietPoints) only those whose accumulated deformation
//! asks for it, and with steady flow (SteadyFlow) not the flowing points between their checks;
//! the others get their stress predicted.
class PointSelection {
 public:
  PointSelection(const QuietSpec& quiet, const ContinuumStartSpec& continuum_start,
                 const SteadyFlowSpec& steady_flow)
      : quiet_spec_(quiet), continuum_start_spec_(continuum_start), flow_spec_(steady_flow) {}

  //! `points` points of a `dimension`-D packing, point i cloned from packings[order.of(i)];
  //! `stress_floor` [Pa] as QuietPoints::start.
  void start(std::size_t points, int dimension, double stress_floor,
             const std::vector<Packing>& packings, const PackingOrder& order);
  //! This update's batch of a material of `points` points: books step.dF with the quiet and
  //! the flowing points.
  DemBatch select(std::size_t points, const materials::MaterialStep& step);
  //! After the stresses are gathered into `stress` (every point's): checks the predictions of
  //! the points that ran DEM, and writes the predicted stresses of those that did not.
  void settle(const std::vector<std::size_t>& points, const DemBatch& batch,
              std::vector<Mat3>& stress);

  //! Every point's quiet state (the same on every rank): checkpoints and statistics.
  const QuietPoints& quiet() const { return quiet_; }
  QuietPoints& quiet() { return quiet_; }
  //! Every point's steady-flow state (the same on every rank).
  const SteadyFlow& flow() const { return flow_; }
  SteadyFlow& flow() { return flow_; }

 private:
  QuietSpec quiet_spec_;
  ContinuumStartSpec continuum_start_spec_;
  SteadyFlowSpec flow_spec_;
  QuietPoints quiet_;
  SteadyFlow flow_;
};

}  // namespace mpm_lig::coupling
