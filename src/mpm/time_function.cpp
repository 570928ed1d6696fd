#include "mpm/time_function.h"

#include <algorithm>
#include <cmath>

#include "core/tensor.h"

namespace mpm_lig::mpm {
namespace {

constexpr double kMinTime = 1e-9;  //!< [s]
constexpr double kMaxTime = 1e12;  //!< [s]

//! t / period modulo 1. A time within round-off of a quarter period counts as exactly that
//! quarter: with a time step that divides T/4, t = n dt carries round-off, and a square wave
//! would otherwise switch one step late now and then, so the triangular displacement of
//! cyclic shear would drift by two steps' worth per slip.
double phase_of(double t, double period) {
  double x = t / period;
  const double quarters = std::round(4.0 * x);
  if (std::abs(4.0 * x - quarters) <= 1e-9 * std::max(1.0, std::abs(quarters)))
    x = 0.25 * quarters;
  return x - std::floor(x);
}

}  // namespace

double TimeFunction::at(double t) const {
  const double phase = phase_of(t, time);  // in [0, 1)
  switch (kind) {
    case Kind::constant:
      return 1.0;
    case Kind::ramp:
      return std::clamp(t / time, 0.0, 1.0);
    case Kind::triangular:
      if (phase < 0.25)
        return 4.0 * phase;
      if (phase < 0.75)
        return 2.0 - 4.0 * phase;
      return 4.0 * phase - 4.0;
    case Kind::square:
      return (phase < 0.25 || phase >= 0.75) ? 1.0 : -1.0;
    case Kind::sine:
      return std::sin(2.0 * kPi * phase);
  }
  return 1.0;
}

TimeFunction TimeFunction::read(const CaseNode& node, const std::string& key) {
  TimeFunction f;
  if (!node.has(key))
    return f;
  const CaseNode fn = node.child(key);
  const std::string type = fn.choice("type", {"constant", "ramp", "triangular", "square", "sine"});
  if (type == "constant")
    return f;
  // Times far from 0 and infinity: t / time stays finite and its phase exact enough (a
  // denormal period would make it infinite and every prescribed value NaN).
  if (type == "ramp") {
    f.kind = Kind::ramp;
    f.time = fn.in_range("time", kMinTime, kMaxTime);
    return f;
  }
  f.kind = type == "triangular" ? Kind::triangular : type == "square" ? Kind::square : Kind::sine;
  f.time = fn.in_range("period", kMinTime, kMaxTime);
  return f;
}

}  // namespace mpm_lig::mpm
