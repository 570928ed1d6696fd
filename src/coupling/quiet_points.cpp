#include "coupling/quiet_points.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/plane_strain.h"

namespace mpm_lig::coupling {

const QuietStatField kQuietStatFields[12] = {
    {"quiet_predictions", &QuietStats::predictions},
    {"quiet_dem_updates", &QuietStats::dem_updates},
    {"quiet_checks", &QuietStats::checks},
    {"quiet_error_sum", &QuietStats::error_sum},
    {"quiet_max_error", &QuietStats::max_error},
    {"quiet_exceeded", &QuietStats::exceeded},
    {"continuum_updates", &QuietStats::continuum_updates},
    {"continuum_switches", &QuietStats::switches},
    {"continuum_jump_sum", &QuietStats::jump_sum},
    {"continuum_max_jump", &QuietStats::max_jump},
    {"continuum_jumps_exceeded", &QuietStats::jumps_exceeded},
    {"continuum_threshold_scale", &QuietStats::threshold_scale}};
static_assert(sizeof(QuietStats) == std::size(kQuietStatFields) * sizeof(double),
              "every QuietStats field needs its checkpoint name in kQuietStatFields");
using namespace plane;

namespace {

//! A tolerance is never tightened below this fraction of the case's.
constexpr double kTightestFraction = 1.0 / 1024.0;
//! The switch thresholds of a continuum start are never halved below this fraction.
constexpr double kSmallestThresholdScale = 1.0 / 64.0;
//! An increment below this fraction of the tolerance is too small to measure moduli on (the
//! packing's stress fluctuations would dominate its secant).
constexpr double kMeasurableStrain = 0.1;
//! A volumetric or deviatoric part smaller than this fraction of the increment measures nothing.
constexpr double kMeasurablePart = 0.1;

//! sin of the mobilised friction angle, (σ1 - σ3) / (σ1 + σ3) compression positive, in the
//! first `d` axes; 1 when the stress is not compressive.
double mobilised_sin_friction(const Mat3& stress, int d) {
  const auto [s1, s3] = extreme_principal_stresses(stress, d);
  if (!(s1 + s3 > 0.0))
    return 1.0;
  return (s1 - s3) / (s1 + s3);
}

}  // namespace

ContinuumStartSpec parse_continuum_start(const CaseNode& node) {
  ContinuumStartSpec s;
  s.enabled = node.get_or<bool>("enabled", true);
  s.strain = node.in_range_or("strain", 1e-7, 0.1, s.strain);
  s.friction_deg = node.in_range_or("friction_deg", 0.1, 89.0, s.friction_deg);
  s.max_jump = node.in_range_or("max_jump", 1e-6, 1.0, s.max_jump);
  return s;
}

QuietSpec parse_quiet(const CaseNode& node) {
  QuietSpec s;
  s.enabled = node.get_or<bool>("enabled", true);
  s.tolerance = node.in_range_or("tolerance", 1e-8, 0.1, s.tolerance);
  s.max_error = node.in_range_or("max_error", 1e-6, 1.0, s.max_error);
  s.check_every = node.get_or<int>("check_every", s.check_every);
  s.cap_friction = node.get_or<bool>("cap_friction", s.cap_friction);
  if (s.check_every < 1 || s.check_every > 1'000'000)
    node.fail("check_every", "must be between 1 and 1000000");
  return s;
}

Mat3 capped_friction(const Mat3& stress, double limit, int d) {
  const double mean = -trace_d(stress, d) / d;  // compression positive
  if (!(mean > 0.0) || mobilised_sin_friction(stress, d) <= limit)
    return stress;
  const Mat3 plane_part = in_plane(stress, d);
  const Mat3 deviator = plane_part + mean * identity_d(d);
  // With the deviator scaled by k, sin φ = k (e1 - e3) / (2 mean + k (e1 + e3)), e1 ≥ e3 its
  // extreme principal values (compression positive; e1 + e3 = 0 in 2D).
  const auto [e1, e3] = extreme_principal_stresses(deviator, d);
  const double k = 2.0 * mean * limit / ((e1 - e3) - limit * (e1 + e3));
  if (!(k >= 0.0 && k < 1.0))
    return stress;
  return stress - plane_part + (-mean * identity_d(d) + k * deviator);
}

void QuietPoints::start(std::size_t points, const QuietSpec& spec, int dimension,
                        double stress_floor, const ContinuumStartSpec& continuum_start) {
  spec_ = spec;
  continuum_start_ = continuum_start;
  dimension_ = dimension;
  stress_floor_ = stress_floor;
  pending_.assign(points, Mat3::Identity());
  anchor_.assign(points, Mat3::Zero());
  predicted_.assign(points, Mat3::Zero());
  rows_.assign(points, Row{});
  for (Row& r : rows_) {
    r.tolerance = spec.tolerance;
    r.continuum = continuum_start.enabled ? 1.0 : 0.0;
  }
  stats_ = QuietStats{};
}

PackingModuli packing_moduli(double wave_modulus, double lateral_modulus, int dimension) {
  // M = K + G and L = K - G in plane strain (K the areal bulk modulus); M = K + 4G/3 and
  // L = K - 2G/3 in 3D.
  const double shear = 0.5 * (wave_modulus - lateral_modulus);
  const double bulk = dimension == 2 ? wave_modulus - shear : wave_modulus - 4.0 * shear / 3.0;
  if (shear > 0.0 && bulk > 0.0 && shear <= wave_modulus && bulk <= wave_modulus)
    return {bulk, shear};
  const double equal = dimension == 2 ? 0.5 * wave_modulus : 3.0 * wave_modulus / 7.0;
  return {equal, equal};
}

void QuietPoints::set_packing(std::size_t point, const Mat3& stress, double wave_modulus,
                              double lateral_modulus) {
  anchor_[point] = stress;
  predicted_[point] = stress;
  Row& r = row(point);
  r.wave_modulus = wave_modulus;
  const PackingModuli moduli = packing_moduli(wave_modulus, lateral_modulus, dimension_);
  r.bulk = moduli.bulk;
  r.shear = moduli.shear;
}

Mat3 QuietPoints::predict(const Mat3& anchor, const Mat3& increment, double bulk,
                          double shear) const {
  const int d = dimension_;
  const StrainParts e = strain_parts(increment, d);
  return anchor + bulk * e.volumetric * identity_d(d) + 2.0 * shear * e.deviatoric +
         spin_of(anchor, increment, d);
}

bool QuietPoints::passes_switch_threshold(std::size_t point) const {
  const double scale = stats_.threshold_scale;
  const double strain = (pending_[point] - Mat3::Identity()).norm();
  const double sin_limit = scale * std::sin(continuum_start_.friction_deg * kDegree);
  return strain >= scale * continuum_start_.strain ||
         mobilised_sin_friction(predicted_[point], dimension_) >= sin_limit;
}

bool QuietPoints::accumulate(std::size_t point, const Mat3& dF) {
  pending_[point] = dF * pending_[point];
  Row& r = row(point);
  predicted_[point] = predict(anchor_[point], pending_[point], r.bulk, r.shear);
  if (r.continuum != 0.0) {
    if (passes_switch_threshold(point))
      return true;
    stats_.continuum_updates += 1.0;
    return false;
  }
  if (!spec_.enabled)
    return true;
  if (spec_.cap_friction && r.yielding != 0.0)
    predicted_[point] = capped_friction(
        predicted_[point], mobilised_sin_friction(anchor_[point], dimension_), dimension_);
  const double strain = (pending_[point] - Mat3::Identity()).norm();
  if (strain >= r.tolerance || r.quiet_updates >= spec_.check_every)
    return true;
  r.quiet_updates += 1.0;
  stats_.predictions += 1.0;
  return false;
}

double QuietPoints::relative_error(std::size_t point, const Mat3& stress) const {
  return plane::relative_error(predicted_[point], stress, stress_floor_);
}

void QuietPoints::book_switch(std::size_t point, const Mat3& stress) {
  const double jump = relative_error(point, stress);
  stats_.switches += 1.0;
  stats_.jump_sum += jump;
  stats_.max_jump = std::max(stats_.max_jump, jump);
  if (jump > continuum_start_.max_jump) {
    stats_.jumps_exceeded += 1.0;
    stats_.threshold_scale = std::max(0.5 * stats_.threshold_scale, kSmallestThresholdScale);
  }
  row(point).continuum = 0.0;
}

void QuietPoints::after_dem(std::size_t point, const Mat3& stress) {
  Row& r = row(point);
  if (r.continuum != 0.0) {
    book_switch(point, stress);
  } else if (r.quiet_updates > 0.0) {
    // The prediction for this increment, against the DEM's answer: an upper bound of the
    // error of the quiet updates before it, whose increments were smaller.
    const double error = relative_error(point, stress);
    stats_.checks += 1.0;
    stats_.error_sum += error;
    stats_.max_error = std::max(stats_.max_error, error);
    if (error > spec_.max_error) {
      stats_.exceeded += 1.0;
      r.tolerance = std::max(0.5 * r.tolerance, kTightestFraction * spec_.tolerance);
    } else if (error < 0.25 * spec_.max_error) {
      r.tolerance = std::min(2.0 * r.tolerance, spec_.tolerance);
    }
  }
  stats_.dem_updates += 1.0;
  measure_moduli(point, stress);
  anchor_[point] = stress;
  predicted_[point] = stress;
  pending_[point] = Mat3::Identity();
  r.quiet_updates = 0.0;
}

void QuietPoints::measure_moduli(std::size_t point, const Mat3& stress) {
  const int d = dimension_;
  const Mat3& increment = pending_[point];
  const StrainParts e = strain_parts(increment, d);
  const double size = e.strain.norm();
  if (!(size >= kMeasurableStrain * spec_.tolerance))
    return;
  const Mat3 change = in_plane(stress - anchor_[point] - spin_of(anchor_[point], increment, d), d);
  Row& r = row(point);
  double bulk = 0.0, shear = 0.0;
  if (std::abs(e.volumetric) >= kMeasurablePart * size)
    bulk = (trace_d(change, d) / d) / e.volumetric;
  if (e.deviatoric.norm() >= kMeasurablePart * size)
    shear = (change.cwiseProduct(e.deviatoric)).sum() / (2.0 * e.deviatoric.squaredNorm());
  // A secant that is not a stiffness (softening, dilatancy under shear, the noise of a small
  // increment) keeps the last one measured; the checks catch what that misses.
  if (std::isfinite(bulk) && bulk > 0.0 && bulk <= r.wave_modulus)
    r.bulk = bulk;
  if (std::isfinite(shear) && shear > 0.0 && shear <= r.wave_modulus)
    r.shear = shear;
  if (e.deviatoric.norm() >= kMeasurablePart * size)
    r.yielding = std::isfinite(shear) && shear <= 0.0 ? 1.0 : 0.0;
}

void QuietPoints::save_row(std::size_t point, double* v) const {
  std::copy(pending_[point].data(), pending_[point].data() + 9, v);
  std::copy(anchor_[point].data(), anchor_[point].data() + 9, v + 9);
  std::copy(predicted_[point].data(), predicted_[point].data() + 9, v + 18);
  const Row& r = row(point);
  const double rest[] = {r.bulk,         r.shear,     r.tolerance, r.quiet_updates,
                         r.wave_modulus, r.continuum, r.yielding};
  std::copy(rest, rest + 7, v + 27);
}

void QuietPoints::restore_row(std::size_t point, const double* v) {
  std::copy(v, v + 9, pending_[point].data());
  std::copy(v + 9, v + 18, anchor_[point].data());
  std::copy(v + 18, v + 27, predicted_[point].data());
  Row& r = row(point);
  r.bulk = v[27];
  r.shear = v[28];
  r.tolerance = v[29];
  r.quiet_updates = v[30];
  r.wave_modulus = v[31];
  r.continuum = v[32];
  r.yielding = v[33];
}

}  // namespace mpm_lig::coupling
