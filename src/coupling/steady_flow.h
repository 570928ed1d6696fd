#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "core/case_node.h"
#include "core/tensor.h"

namespace mpm_lig::coupling {

//! Case node "steady_flow" of a dem_rve material (absent: off).
struct SteadyFlowSpec {
  bool enabled = false;
  double window = 0.02;         //!< shear strain γ of one window of DEM updates
  double stress_change = 0.1;   //!< largest change of p and of q/p between two windows (relative)
  double dilatancy = 0.05;      //!< largest |Δε_v / Δγ| over a window
  double volume_change = 2e-3;  //!< |ε_v| since the flow began that ends it
  double turn_deg = 30.0;       //!< angle between deviatoric strains that ends a flow
  double max_error = 0.15;      //!< check error (relative to |σ|) that ends a flow
  int check_every = 10;         //!< predicted updates of a flowing point before a check
};

SteadyFlowSpec parse_steady_flow(const CaseNode& node);

//! What the steady flows measured over the run.
struct SteadyFlowStats {
  double predictions = 0.0;    //!< point-updates answered from the flow (no DEM)
  double entries = 0.0;        //!< flows begun
  double checks = 0.0;         //!< DEM updates of flowing points (checks and exits)
  double error_sum = 0.0;      //!< sum of their relative errors
  double max_error = 0.0;      //!< largest of them
  double exceeded = 0.0;       //!< checks above max_error (each ended its flow)
  double drifts = 0.0;         //!< flows ended by a window of checks that was not steady
  double turns = 0.0;          //!< flows ended by a turn of the shear direction
  double volume_exits = 0.0;   //!< flows ended by a volume change
  double skipped_shear = 0.0;  //!< shear strain γ the flowing points' RVEs did not run
};

//! A SteadyFlowStats field and its name in a checkpoint.
struct SteadyFlowStatField {
  const char* name;
  double SteadyFlowStats::*value;
};
//! Every SteadyFlowStats field under its checkpoint name (a new statistic: one field, one line).
extern const SteadyFlowStatField kSteadyFlowStatFields[10];

//! Points in steady critical-state flow answered from their own recent response
//! (docs/dem_work.md §6).
//!
//! A point's DEM updates are grouped into windows of shear strain γ ≥ `window`. When two
//! windows in a row have the same mean pressure p and stress ratio q/p (within
//! `stress_change`), the same shear direction (within `turn_deg`) and no volume change
//! (|Δε_v/Δγ| ≤ `dilatancy`), the point flows: its stress is the last window's mean, changed
//! by the packing's bulk modulus (scaled by √(p/p0)) times the volume change since, and its
//! RVE does not run. At critical state the stress follows the stretching, not the material
//! spin (in a steady simple shear σ is constant while the material rotates), so the flow's
//! stress and its RVE both keep their orientation in space; a turn of the stretching ends the
//! flow. A packing at critical state has forgotten its path, so the RVE is not made to catch
//! up with the shear it missed: its next DEM update runs that update's own increment and the
//! volume change the point had since the last one. After `check_every` predicted updates that
//! DEM update is a check of the prediction; an error above `max_error`, a turn of the
//! increment's shear direction beyond `turn_deg` or a volume change beyond `volume_change`
//! since the flow began end the flow (the point runs DEM every update again and measures new
//! windows). The checks' own shear makes windows too, on the RVE's slowed path: one that
//! differs from the window before by more than `stress_change` ends the flow (a packing that
//! was not at critical state after all drifts, at 1/(`check_every` + 1) of its pace; windows
//! are held to the window before and to the flow's first).
//!
//! All state is replicated on every rank and updated from replicated data only, like
//! QuietPoints: every rank takes the same decisions, whatever the rank count.
class SteadyFlow {
 public:
  //! Per-point values in a checkpoint row (the Row members and the tensors, see save_row).
  static constexpr int kValues = 73;
  //! The Row's values in a checkpoint row, after the 6 tensors.
  static constexpr std::size_t kRowValues = 19;

  //! `points` points of a `dimension`-D packing; `stress_floor` [Pa]: the smallest pressure a
  //! flow is recognised at, and what keeps relative errors near zero stress finite.
  void start(std::size_t points, const SteadyFlowSpec& spec, int dimension, double stress_floor);
  //! `point` before any update: its packing's mean pressure and bulk modulus (the packing's
  //! probe, PackingModuli), the flow's volumetric stiffness at that pressure.
  void set_packing(std::size_t point, double pressure, double bulk_modulus);
  bool enabled() const { return spec_.enabled; }
  bool flowing(std::size_t point) const { return row(point).flowing != 0.0; }

  //! Books the MPM increment `dF` of a flowing `point`; true when it must run DEM now (a
  //! check or the end of its flow) under catch_up(point), false when its stress is
  //! predicted(point).
  bool accumulate(std::size_t point, const Mat3& dF);
  //! The increment a flowing point's RVE runs when it runs: valid after accumulate() returned
  //! true.
  const Mat3& catch_up(std::size_t point) const { return catch_up_[point]; }
  const Mat3& predicted(std::size_t point) const { return anchor_[point]; }
  //! After a DEM update of `point` under `increment` that gave `stress`: a flowing point's
  //! check, any other point's window.
  void after_dem(std::size_t point, const Mat3& increment, const Mat3& stress);

  //! The increment an RVE runs after missing `pending`, with `dF` now: dF · J^(1/d) in the
  //! plane (J: the volume ratio of `pending`; testable alone).
  Mat3 reduced_increment(const Mat3& dF, const Mat3& pending) const;

  const SteadyFlowStats& stats() const { return stats_; }
  void save_row(std::size_t point, double* values) const;
  void restore_row(std::size_t point, const double* values);
  void restore_stats(const SteadyFlowStats& stats) { stats_ = stats; }

 private:
  //! Sums over the DEM updates of the window being measured, weighted by their shear.
  struct Window {
    double shear = 0.0;       //!< γ
    double volumetric = 0.0;  //!< ε_v
    double pressure = 0.0;    //!< Σ p Δγ
    double ratio = 0.0;       //!< Σ (q/p) Δγ
    double updates = 0.0;     //!< DEM updates in it
  };
  struct Row {
    Window window;
    double last_pressure = 0.0, last_ratio = 0.0;  //!< the previous window's means
    double last_dilatancy = 0.0;                   //!< and its |ε_v| / γ
    double flow_pressure = 0.0, flow_ratio = 0.0;  //!< the means when the flow began
    double has_last = 0.0;                         //!< 1 once a window was closed
    double flowing = 0.0;                          //!< 1 while the point flows
    double flow_updates = 0.0;                     //!< predicted updates since its last DEM
    double flow_volumetric = 0.0;                  //!< ε_v since the flow began
    double samples = 0.0;                          //!< stresses averaged into the anchor
    double typical_shear = 0.0;                    //!< the flow's γ per update when it began
    double checking = 0.0;  //!< 1 while a flowing point's DEM update (check or end) runs
    double packing_pressure = 0.0, packing_bulk = 0.0;  //!< set_packing()
  };
  //! Every value of `r`, in the order of a checkpoint row (one list for saving and restoring).
  static std::array<double*, kRowValues> values_of(Row& r);
  Row& row(std::size_t point) { return rows_[point]; }
  const Row& row(std::size_t point) const { return rows_[point]; }
  void add_to_window(std::size_t point, const Mat3& increment, const Mat3& stress);
  void close_window(std::size_t point);
  //! An empty window of `point` (its sums cleared).
  void start_window(std::size_t point);
  //! Whether the window just measured, `w`, is as steady as a flow needs.
  bool steady(std::size_t point, const Window& w, const Mat3& shear) const;
  //! The flow's volumetric stiffness at its present pressure.
  double flow_bulk(std::size_t point) const;
  void check(std::size_t point, const Mat3& stress);
  void end_flow(std::size_t point);

  SteadyFlowSpec spec_;
  int dimension_ = 2;
  double stress_floor_ = 1.0;
  std::vector<Mat3> pending_;     //!< increment since the last DEM update of a flowing point
  std::vector<Mat3> catch_up_;    //!< what a flowing point's RVE runs when it runs
  std::vector<Mat3> anchor_;      //!< the flow's stress (the window mean, then checks)
  std::vector<Mat3> direction_;   //!< the flow's unit shear direction
  std::vector<Mat3> stress_sum_;  //!< Σ σ Δγ of the window being measured
  std::vector<Mat3> shear_sum_;   //!< Σ Δe (deviatoric strain) of that window
  std::vector<Mat3> last_shear_;  //!< the previous window's unit shear direction
  std::vector<Row> rows_;
  SteadyFlowStats stats_;
};

}  // namespace mpm_lig::coupling
