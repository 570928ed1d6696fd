#include "coupling/steady_flow.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "core/plane_strain.h"

namespace mpm_lig::coupling {

const SteadyFlowStatField kSteadyFlowStatFields[10] = {
    {"flow_predictions", &SteadyFlowStats::predictions},
    {"flow_entries", &SteadyFlowStats::entries},
    {"flow_checks", &SteadyFlowStats::checks},
    {"flow_error_sum", &SteadyFlowStats::error_sum},
    {"flow_max_error", &SteadyFlowStats::max_error},
    {"flow_exceeded", &SteadyFlowStats::exceeded},
    {"flow_drifts", &SteadyFlowStats::drifts},
    {"flow_turns", &SteadyFlowStats::turns},
    {"flow_volume_exits", &SteadyFlowStats::volume_exits},
    {"flow_skipped_shear", &SteadyFlowStats::skipped_shear}};
static_assert(sizeof(SteadyFlowStats) == std::size(kSteadyFlowStatFields) * sizeof(double),
              "every SteadyFlowStats field needs its checkpoint name in kSteadyFlowStatFields");

using namespace plane;

namespace {

//! A check's stress joins the anchor's running mean, over at most this many samples (the
//! window mean counts as one).
constexpr double kMostSamples = 10.0;
//! A path's shear below this fraction of the flow's γ per update when it began is too small
//! to tell its direction.
constexpr double kMeasurableShear = 0.25;
constexpr int kTensorValues = 6 * 9;

double stress_ratio(const Mat3& stress, int d) {
  const double p = mean_pressure(stress, d);
  return p > 0.0 ? deviatoric_stress(stress, d) / p : 0.0;
}

//! Cosine of the angle between two deviatoric tensors (0 when either is zero).
double cosine(const Mat3& a, const Mat3& b) {
  const double n = a.norm() * b.norm();
  return n > 0.0 ? a.cwiseProduct(b).sum() / n : 0.0;
}

}  // namespace

SteadyFlowSpec parse_steady_flow(const CaseNode& node) {
  SteadyFlowSpec s;
  s.enabled = node.get_or<bool>("enabled", true);
  s.window = node.in_range_or("window", 1e-4, 1.0, s.window);
  s.stress_change = node.in_range_or("stress_change", 1e-4, 1.0, s.stress_change);
  s.dilatancy = node.in_range_or("dilatancy", 1e-4, 1.0, s.dilatancy);
  s.volume_change = node.in_range_or("volume_change", 1e-6, 0.1, s.volume_change);
  s.turn_deg = node.in_range_or("turn_deg", 1.0, 90.0, s.turn_deg);
  s.max_error = node.in_range_or("max_error", 1e-4, 1.0, s.max_error);
  s.check_every = node.get_or<int>("check_every", s.check_every);
  if (s.check_every < 1 || s.check_every > 1'000'000)
    node.fail("check_every", "must be between 1 and 1000000");
  return s;
}

void SteadyFlow::start(std::size_t points, const SteadyFlowSpec& spec, int dimension,
                       double stress_floor) {
  spec_ = spec;
  dimension_ = dimension;
  stress_floor_ = stress_floor;
  for (auto* v : {&pending_, &catch_up_})
    v->assign(points, Mat3::Identity());
  for (auto* v : {&anchor_, &direction_, &stress_sum_, &shear_sum_, &last_shear_})
    v->assign(points, Mat3::Zero());
  rows_.assign(points, Row{});
  stats_ = SteadyFlowStats{};
}

void SteadyFlow::set_packing(std::size_t point, double pressure, double bulk_modulus) {
  Row& r = row(point);
  r.packing_pressure = std::max(pressure, stress_floor_);
  r.packing_bulk = bulk_modulus;
}

double SteadyFlow::flow_bulk(std::size_t point) const {
  const Row& r = row(point);
  if (!(r.packing_pressure > 0.0))
    return 0.0;  // no packing given (a unit test of the windows alone)
  const double p = std::max(mean_pressure(anchor_[point], dimension_), stress_floor_);
  return r.packing_bulk * std::sqrt(p / r.packing_pressure);
}

Mat3 SteadyFlow::reduced_increment(const Mat3& dF, const Mat3& pending) const {
  const int d = dimension_;
  const double volume_ratio = pending.topLeftCorner(d, d).determinant();
  Mat3 dilation = Mat3::Identity();
  dilation.topLeftCorner(d, d) *= std::pow(volume_ratio, 1.0 / d);
  return dF * dilation;
}

bool SteadyFlow::accumulate(std::size_t point, const Mat3& dF) {
  const int d = dimension_;
  Row& r = row(point);
  const StrainParts e = strain_parts(dF, d);
  catch_up_[point] = reduced_increment(dF, pending_[point]);
  pending_[point] = dF * pending_[point];
  r.flow_volumetric += e.volumetric;
  anchor_[point] += flow_bulk(point) * e.volumetric * identity_d(d);
  const double shear = engineering_shear(e.deviatoric);
  // The path's direction is that of the shear since the last DEM update (up to check_every
  // increments): one increment of a noisy velocity field does not turn a flow.
  const Mat3 path = strain_parts(pending_[point], d).deviatoric;
  const bool measurable = engineering_shear(path) >= kMeasurableShear * r.typical_shear;
  r.checking = 1.0;
  if (measurable && cosine(path, direction_[point]) < std::cos(spec_.turn_deg * kDegree)) {
    stats_.turns += 1.0;
    end_flow(point);
    return true;
  }
  if (std::abs(r.flow_volumetric) > spec_.volume_change) {
    stats_.volume_exits += 1.0;
    end_flow(point);
    return true;
  }
  if (r.flow_updates >= spec_.check_every)
    return true;
  r.checking = 0.0;
  r.flow_updates += 1.0;
  stats_.predictions += 1.0;
  stats_.skipped_shear += shear;
  return false;
}

void SteadyFlow::end_flow(std::size_t point) {
  Row& r = row(point);
  r.flowing = 0.0;
  r.has_last = 0.0;
  start_window(point);
}

void SteadyFlow::start_window(std::size_t point) {
  row(point).window = Window{};
  stress_sum_[point] = shear_sum_[point] = Mat3::Zero();
}

void SteadyFlow::after_dem(std::size_t point, const Mat3& increment, const Mat3& stress) {
  Row& r = row(point);
  const bool was_flowing = r.flowing != 0.0;  // false when this update ended the flow
  if (r.checking != 0.0) {
    // A flowing point's check, or the DEM update that ended its flow.
    check(point, stress);
    pending_[point] = Mat3::Identity();
    r.flow_updates = 0.0;
    r.checking = 0.0;
    if (was_flowing && r.flowing == 0.0)
      return;  // a failed check: new windows from the next update on
  }
  add_to_window(point, increment, stress);
}

void SteadyFlow::check(std::size_t point, const Mat3& stress) {
  Row& r = row(point);
  const double error = relative_error(anchor_[point], stress, stress_floor_);
  stats_.checks += 1.0;
  stats_.error_sum += error;
  stats_.max_error = std::max(stats_.max_error, error);
  const bool missed = !(error <= spec_.max_error);  // a NaN stress misses too
  if (missed)
    stats_.exceeded += 1.0;
  if (r.flowing == 0.0)
    return;  // the update that ended a flow by a turn or a volume change
  if (missed) {
    end_flow(point);
    return;
  }
  r.samples = std::min(r.samples + 1.0, kMostSamples);
  anchor_[point] += (stress - anchor_[point]) / r.samples;
}

void SteadyFlow::add_to_window(std::size_t point, const Mat3& increment, const Mat3& stress) {
  const int d = dimension_;
  Row& r = row(point);
  const StrainParts e = strain_parts(increment, d);
  const double shear = engineering_shear(e.deviatoric);
  Window& w = r.window;
  w.shear += shear;
  w.volumetric += e.volumetric;
  w.pressure += mean_pressure(stress, d) * shear;
  w.ratio += stress_ratio(stress, d) * shear;
  w.updates += 1.0;
  stress_sum_[point] += stress * shear;
  shear_sum_[point] += e.deviatoric;
  if (w.shear >= spec_.window)
    close_window(point);
}

bool SteadyFlow::steady(std::size_t point, const Window& w, const Mat3& shear) const {
  const Row& r = row(point);
  const double pressure = w.pressure / w.shear;
  const double ratio = w.ratio / w.shear;
  const auto same = [&](double value, double reference) {
    return std::abs(value - reference) <= spec_.stress_change * value;
  };
  // A flowing point's windows are made of its checks, whose increments carry the volume
  // change of the whole flow: its volume is held by volume_change instead. They are held to
  // the flow's first window as well as to the one before, so that no slow drift goes on.
  const bool flowing = r.flowing != 0.0;
  const bool constant_volume = flowing || (std::abs(w.volumetric) <= spec_.dilatancy * w.shear &&
                                           r.last_dilatancy <= spec_.dilatancy);
  const bool since_begun =
      !flowing || (same(pressure, r.flow_pressure) && same(ratio, r.flow_ratio));
  return r.has_last != 0.0 && pressure > stress_floor_ && same(pressure, r.last_pressure) &&
         same(ratio, r.last_ratio) && constant_volume && since_begun &&
         cosine(shear, last_shear_[point]) >= std::cos(spec_.turn_deg * kDegree);
}

void SteadyFlow::close_window(std::size_t point) {
  Row& r = row(point);
  const Window w = r.window;
  const Mat3 shear =
      shear_sum_[point].norm() > 0.0 ? Mat3(shear_sum_[point].normalized()) : Mat3(Mat3::Zero());
  const bool is_steady = steady(point, w, shear);
  if (r.flowing != 0.0 && !is_steady) {
    stats_.drifts += 1.0;
    end_flow(point);
    return;
  }
  if (is_steady) {
    if (r.flowing == 0.0) {
      r.flowing = 1.0;
      r.flow_updates = 0.0;
      r.flow_volumetric = 0.0;
      r.typical_shear = w.shear / w.updates;
      r.flow_pressure = w.pressure / w.shear;
      r.flow_ratio = w.ratio / w.shear;
      stats_.entries += 1.0;
    }
    direction_[point] = shear;
    r.samples = 1.0;
    anchor_[point] = stress_sum_[point] / w.shear;
  }
  r.last_pressure = w.pressure / w.shear;
  r.last_ratio = w.ratio / w.shear;
  r.last_dilatancy = std::abs(w.volumetric) / w.shear;
  r.has_last = 1.0;
  last_shear_[point] = shear;
  start_window(point);
}

std::array<double*, SteadyFlow::kRowValues> SteadyFlow::values_of(Row& r) {
  return {&r.window.shear,   &r.window.volumetric, &r.window.pressure, &r.window.ratio,
          &r.window.updates, &r.last_pressure,     &r.last_ratio,      &r.last_dilatancy,
          &r.has_last,       &r.flowing,           &r.flow_updates,    &r.flow_volumetric,
          &r.samples,        &r.typical_shear,     &r.checking,        &r.packing_pressure,
          &r.packing_bulk,   &r.flow_pressure,     &r.flow_ratio};
}

void SteadyFlow::save_row(std::size_t point, double* v) const {
  const Mat3* tensors[] = {&pending_[point],    &anchor_[point],    &direction_[point],
                           &stress_sum_[point], &shear_sum_[point], &last_shear_[point]};
  for (const Mat3* t : tensors)
    v = std::copy(t->data(), t->data() + 9, v);
  Row copy = row(point);
  for (const double* x : values_of(copy))
    *v++ = *x;
}

void SteadyFlow::restore_row(std::size_t point, const double* v) {
  Mat3* tensors[] = {&pending_[point],    &anchor_[point],    &direction_[point],
                     &stress_sum_[point], &shear_sum_[point], &last_shear_[point]};
  for (Mat3* t : tensors) {
    std::copy(v, v + 9, t->data());
    v += 9;
  }
  for (double* x : values_of(row(point)))
    *x = *v++;
}

static_assert(SteadyFlow::kValues == kTensorValues + SteadyFlow::kRowValues,
              "a SteadyFlow row: 6 tensors and the Row values");

}  // namespace mpm_lig::coupling
