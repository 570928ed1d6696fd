#pragma once

#include <cstddef>

#include "coupling/quiet_points.h"
#include "coupling/rve_balance.h"
#include "coupling/steady_flow.h"
#include "materials/statistics.h"

namespace mpm_lig::coupling {

//! Cost counters of a dem_rve material: the same on every rank except the times, this rank's.
struct DemCost {
  std::size_t simulations = 0;         //!< RVEs (all ranks)
  double particle_steps = 0.0;         //!< DEM grain-steps so far, each RVE counted once
  double compute_seconds = 0.0;        //!< this rank's time in its RVEs
  double communication_seconds = 0.0;  //!< this rank's time exchanging stresses (waits included)
  double preparation_seconds = 0.0;    //!< prepare(): packings made or loaded
  double migration_seconds = 0.0;      //!< this rank's time moving RVEs (waits included)
};

//! The statistics of the DEM family that every run's summary holds (registered at zero, so a
//! continuum run's too): "rve_count", "dem_particle_steps" (its rate on the progress line),
//! the DEM's parts of the wall time "time_split.{dem,communication,preparation}" (rank 0's),
//! and with particle-steps every rank's DEM time "dem_seconds_per_rank" and its
//! "load_imbalance" (max / mean: 1 is perfect balance, the excess is waiting).
materials::Report dem_statistics(const DemCost& cost);

//! How busy the rank groups of a material's simulations were, step by step. Work is in DEM
//! particle-steps, an update's fixed cost included; efficiency = work / (groups × makespan).
struct SteppingCounters {
  double groups = 0.0;
  StepTotals predicted;            //!< from the predicted costs
  StepTotals measured;             //!< from the measured steps
  StepTotals seconds;              //!< the owners' measured times
  double migrations = 0.0;         //!< RVEs moved to another group
  double rebalances = 0.0;         //!< updates before which RVEs moved
  double migration_seconds = 0.0;  //!< this rank's time moving them
};

//! Shares of the particle-steps (coupling::DemWork sums): at substeps.max, in packings at
//! low stress, in quiet updates ("dem_work_shares", with particle-steps).
void add_work_shares(materials::Report& report, double at_max, double low_stress, double quiet);
//! "stepping": the efficiencies (the measured one on the progress line), the mean group's
//! waiting for the busiest one and its share of the wall time, the migrations.
void add_stepping(materials::Report& report, const SteppingCounters& s);
//! "quiet_points": predicted and computed updates, the checks of the predictions.
void add_quiet_points(materials::Report& report, const QuietStats& q);
//! "steady_flow": predicted updates, flows begun and ended, the checks of the predictions.
void add_steady_flow(materials::Report& report, const SteadyFlowStats& f);
//! "start_as_continuum": the switches of `points` points from continuum to DEM, their jumps.
void add_continuum_start(materials::Report& report, const QuietStats& q, double points);

}  // namespace mpm_lig::coupling
