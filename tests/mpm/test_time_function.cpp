// Time functions of prescribed velocities and tractions, against their definitions.
#include <gtest/gtest.h>

#include "mpm/time_function.h"

namespace mpm_lig::mpm {
namespace {

TimeFunction make(TimeFunction::Kind kind, double time) {
  TimeFunction f;
  f.kind = kind;
  f.time = time;
  return f;
}

TEST(TimeFunction, ShapesOverOnePeriod) {
  const auto ramp = make(TimeFunction::Kind::ramp, 2.0);
  EXPECT_DOUBLE_EQ(ramp.at(0.5), 0.25);
  EXPECT_DOUBLE_EQ(ramp.at(3.0), 1.0);
  const auto triangle = make(TimeFunction::Kind::triangular, 4.0);
  EXPECT_DOUBLE_EQ(triangle.at(0.0), 0.0);
  EXPECT_DOUBLE_EQ(triangle.at(1.0), 1.0);
  EXPECT_DOUBLE_EQ(triangle.at(2.0), 0.0);
  EXPECT_DOUBLE_EQ(triangle.at(3.0), -1.0);
  EXPECT_DOUBLE_EQ(triangle.at(4.5), 0.5);
  const auto square = make(TimeFunction::Kind::square, 4.0);
  EXPECT_DOUBLE_EQ(square.at(0.5), 1.0);
  EXPECT_DOUBLE_EQ(square.at(2.0), -1.0);
  EXPECT_DOUBLE_EQ(square.at(3.5), 1.0);
  const auto sine = make(TimeFunction::Kind::sine, 4.0);
  EXPECT_NEAR(sine.at(1.0), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(make(TimeFunction::Kind::constant, 1.0).at(123.0), 1.0);
}

TEST(TimeFunction, SquareVelocityGivesTriangularDisplacementAboutZero) {
  // Cyclic simple shear: integrating the square wave returns to 0 after each period
  // and stays within [0, T/4] (a triangle starting upward).
  const auto square = make(TimeFunction::Kind::square, 1.0);
  const double dt = 1e-4;
  double u = 0.0, top = 0.0, bottom = 0.0;
  for (int k = 0; k < 30000; ++k) {
    u += square.at((k + 0.5) * dt) * dt;
    top = std::max(top, u);
    bottom = std::min(bottom, u);
  }
  EXPECT_NEAR(u, 0.0, 1e-9);
  EXPECT_NEAR(top, 0.25, 1e-9);
  EXPECT_NEAR(bottom, -0.25, 1e-9);
}

TEST(TimeFunction, SquareSwitchesOnTimeWhenTheStepDividesAQuarterPeriod) {
  // Evaluated at accumulated step starts t += dt (round-off in t), as the solver does:
  // the displacement must hit +-T/4 exactly and not drift over many periods.
  const auto square = make(TimeFunction::Kind::square, 0.04);
  const double dt = 2e-4;  // 50 steps per quarter period
  double t = 0.0, u = 0.0, top = 0.0, bottom = 0.0;
  for (int k = 0; k < 200 * 30; ++k) {
    u += square.at(t) * dt;
    t += dt;
    top = std::max(top, u);
    bottom = std::min(bottom, u);
  }
  EXPECT_NEAR(u, 0.0, 1e-12);
  EXPECT_NEAR(top, 0.01, 1e-12);
  EXPECT_NEAR(bottom, -0.01, 1e-12);
}

}  // namespace
}  // namespace mpm_lig::mpm
