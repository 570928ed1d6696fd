#pragma once

#include <cstddef>
#include <vector>

#include "core/case_node.h"
#include "core/tensor.h"

namespace mpm_lig::coupling {

//! Case node "quiet" of a dem_rve material (absent: off, every point runs DEM every step).
struct QuietSpec {
  bool enabled = false;
  double tolerance = 1e-4;  //!< |F_pending - 1| below which a point's stress is predicted
  double max_error = 0.02;  //!< prediction error (relative to |σ|) that tightens a tolerance
  int check_every = 50;     //!< a point quiet this many updates in a row runs DEM (a check)
  //! A yielding point's prediction never mobilises more friction than its last DEM answer: the
  //! secant it keeps from before it yielded would carry its stress past what the grains hold
  //! (docs/dem_work.md §10). A point yields while its last measurable shear secant was not a
  //! stiffness (its deviator did not grow along its deviatoric strain).
  bool cap_friction = false;
};

//! `stress` (tension positive) with its in-plane deviator scaled down so that its mobilised
//! friction, sin φ = (σ1 − σ3)/(σ1 + σ3) compression positive over the first `d` axes, is at
//! most `limit`; its mean stress and out-of-plane part kept. Unchanged where it is below
//! `limit` or not compressive.
Mat3 capped_friction(const Mat3& stress, double limit, int d);

QuietSpec parse_quiet(const CaseNode& node);

//! Case node "start_as_continuum" of a dem_rve material (absent: off, every point is DEM from
//! the start). A point starts as its packing's elastic continuum and switches to its own RVE
//! for good once either threshold is passed.
struct ContinuumStartSpec {
  bool enabled = false;
  double strain = 1e-4;        //!< |F - 1| since the start that switches a point to DEM
  double friction_deg = 10.0;  //!< mobilised friction angle that switches a point to DEM
  double max_jump = 0.05;      //!< stress jump at a switch (relative to |σ|) that is too large
};

ContinuumStartSpec parse_continuum_start(const CaseNode& node);

//! Isotropic moduli of a packing from its probe: constrained (P-wave) modulus M and lateral
//! modulus L (Δσ_yy / ε_xx under uniaxial strain) give G = (M - L) / 2 and K = M - G (2D) or
//! M - 4G/3 (3D), or equal K and G with that M if that pair is not a stiffness.
struct PackingModuli {
  double bulk;
  double shear;
};
PackingModuli packing_moduli(double wave_modulus, double lateral_modulus, int dimension);

//! What the checks of the predictions measured over the run.
struct QuietStats {
  double predictions = 0.0;  //!< point-updates whose stress was predicted (no DEM)
  double dem_updates = 0.0;  //!< point-updates that ran DEM
  double checks = 0.0;       //!< DEM updates that followed a prediction, i.e. checked one
  double error_sum = 0.0;    //!< sum of the checked predictions' relative errors
  double max_error = 0.0;    //!< largest checked relative error
  double exceeded = 0.0;     //!< checks above max_error (each tightened that point's tolerance)
  double continuum_updates = 0.0;  //!< point-updates of points not yet switched to DEM
  double switches = 0.0;           //!< points switched from the continuum to their RVE
  double jump_sum = 0.0;           //!< sum of the relative stress jumps at the switches
  double max_jump = 0.0;           //!< largest relative stress jump at a switch
  double jumps_exceeded = 0.0;     //!< switches above max_jump (each halved the thresholds)
  double threshold_scale = 1.0;    //!< the switch thresholds' factor (halved by such a jump)
};

//! A QuietStats field and its name in a checkpoint.
struct QuietStatField {
  const char* name;
  double QuietStats::*value;
};
//! Every QuietStats field under its checkpoint name (a new statistic: one field, one line here).
extern const QuietStatField kQuietStatFields[12];

//! Quiet points: a point whose deformation since its last DEM update is below a tolerance gets
//! its stress predicted from its own packing's response, measured on its own DEM updates (an
//! isotropic secant: bulk and shear moduli of the last update's volumetric and deviatoric
//! parts), plus the rotation of the stress it had; the DEM catches up with the accumulated
//! increment once the tolerance is passed, or after `check_every` quiet updates. Every DEM
//! update that follows a prediction compares the two; an error above `max_error` halves the
//! point's tolerance, an error below a quarter of it doubles it back towards the case's.
//!
//! With a continuum start, a point is first a quiet point that never runs DEM: its stress is
//! the prediction from its packing's moduli until |F - 1| or its mobilised friction passes a
//! threshold; its RVE (the packing it was cloned from, untouched until then) then catches up
//! with the whole accumulated deformation in one DEM update, and the difference between the
//! two stresses is the jump the switch makes. A jump above `max_jump` halves the thresholds of
//! the points still continuum (the strain and the sine of the angle, down to 1/64). After the
//! switch the point is DEM, quiet or not.
//!
//! All state is replicated on every rank and updated from replicated data only (the MPM
//! increments and the gathered stresses): every rank takes the same decisions, whatever the
//! rank count. docs/DESIGN.md §8.
class QuietPoints {
 public:
  //! Per-point values in a checkpoint row: pending (9), anchor stress (9), predicted (9),
  //! bulk, shear, tolerance, quiet updates in a row, wave modulus, still continuum (1 or 0),
  //! yielding (1 or 0).
  static constexpr int kValues = 34;

  //! `points` points of a `dimension`-D packing; `stress_floor` [Pa] keeps relative errors of
  //! points near zero stress finite.
  void start(std::size_t points, const QuietSpec& spec, int dimension, double stress_floor,
             const ContinuumStartSpec& continuum_start = ContinuumStartSpec{});
  //! Whether any point's stress may be predicted (quiet points or a continuum start).
  bool enabled() const { return spec_.enabled || continuum_start_.enabled; }
  bool quiet_enabled() const { return spec_.enabled; }
  bool continuum_start_enabled() const { return continuum_start_.enabled; }
  //! Whether `point` is still its packing's continuum (never ran DEM).
  bool is_continuum(std::size_t point) const { return row(point).continuum != 0.0; }
  //! `point` before any update: its packing's stress, constrained (P-wave) modulus M and
  //! lateral modulus L. The moduli start at packing_moduli(M, L); a secant measured later is
  //! bounded by M (a larger one is the noise of a small increment).
  void set_packing(std::size_t point, const Mat3& stress, double wave_modulus,
                   double lateral_modulus);

  //! Books the MPM increment `dF` of `point`; true when it must run DEM now (with
  //! pending(point) as its increment), false when its stress is predicted (predicted(point)).
  bool accumulate(std::size_t point, const Mat3& dF);
  const Mat3& pending(std::size_t point) const { return pending_[point]; }
  //! The predicted stress of a quiet point (valid after accumulate() returned false).
  const Mat3& predicted(std::size_t point) const { return predicted_[point]; }
  //! After a DEM update of `point` under pending(point) that gave `stress`: check the
  //! prediction, measure the secant moduli, start a new quiet interval.
  void after_dem(std::size_t point, const Mat3& stress);
  //! The stress the moduli predict under `increment` from `anchor` (testable alone).
  Mat3 predict(const Mat3& anchor, const Mat3& increment, double bulk, double shear) const;

  double tolerance(std::size_t point) const { return row(point).tolerance; }
  const QuietStats& stats() const { return stats_; }

  //! Checkpoint: `values` gets kValues per point; the run statistics separately (stats(),
  //! by the names of kQuietStatFields).
  void save_row(std::size_t point, double* values) const;
  void restore_row(std::size_t point, const double* values);
  void restore_stats(const QuietStats& stats) { stats_ = stats; }

 private:
  struct Row {
    double bulk = 0.0, shear = 0.0;  //!< secant moduli measured on this point's RVE
    double tolerance = 0.0;
    double quiet_updates = 0.0;  //!< predicted updates since the last DEM update
    double wave_modulus = 0.0;   //!< the packing's M: the largest modulus accepted
    double continuum = 0.0;      //!< 1 until the point switches to DEM (continuum start)
    double yielding = 0.0;       //!< 1 while its last measurable shear secant was refused
  };
  Row& row(std::size_t point) { return rows_[point]; }
  const Row& row(std::size_t point) const { return rows_[point]; }
  void measure_moduli(std::size_t point, const Mat3& stress);
  //! Whether a continuum point has passed a switch threshold under its pending increment.
  bool passes_switch_threshold(std::size_t point) const;
  void book_switch(std::size_t point, const Mat3& stress);
  //! |predicted - stress| / |stress| (the stress floor keeps it finite near zero stress).
  double relative_error(std::size_t point, const Mat3& stress) const;

  QuietSpec spec_;
  ContinuumStartSpec continuum_start_;
  int dimension_ = 2;
  double stress_floor_ = 1.0;
  std::vector<Mat3> pending_;    //!< increment since the last DEM update
  std::vector<Mat3> anchor_;     //!< stress at the last DEM update
  std::vector<Mat3> predicted_;  //!< last predicted stress
  std::vector<Row> rows_;
  QuietStats stats_;
};

}  // namespace mpm_lig::coupling
