#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "driver.h"
#include "materials/linear_elastic.h"
#include "materials/strain_increment.h"

namespace mpm_lig::materials {
namespace {

using testing::rotation;
using testing::step;

const Elasticity kElastic = Elasticity::from_moduli(10e6, 0.3);

TEST(Kinematics, RigidRotationGivesNoStrainAndTheExactRotation) {
  for (const double angle : {1e-6, 0.1, 1.0, 2.5}) {
    const Mat3 q = rotation(Vec3(1.0, -2.0, 0.5), angle);
    const StrainIncrement inc = split_increment(q);
    EXPECT_LT(inc.strain.norm(), 1e-14) << angle;
    EXPECT_LT((inc.rotation - q).norm(), 1e-14) << angle;
  }
}

TEST(Kinematics, SmallIncrementIsTheVelocityGradient) {
  Mat3 l;
  l << 0.3, -0.2, 0.1, 0.5, -0.4, 0.0, 0.2, 0.7, 0.1;
  const double dt = 1e-6;
  const StrainIncrement inc = split_increment(Mat3::Identity() + dt * l);
  // First order in dt: the midpoint terms are O(dt^2 |L|^2).
  const double second_order = dt * dt * l.squaredNorm();
  EXPECT_LT((inc.strain - 0.5 * dt * (l + l.transpose())).norm(), second_order);
  const Mat3 spin_step = inc.rotation - Mat3::Identity();
  EXPECT_LT((spin_step - 0.5 * dt * (l - l.transpose())).norm(), second_order);
}

TEST(LinearElastic, UniaxialStrainMatchesTheConstrainedModulus) {
  LinearElastic m(2000.0, kElastic);
  m.add_points(1);
  const int steps = 50;
  const double total = -2e-3;  // compression
  const double stretch = std::pow(1.0 + total, 1.0 / steps);
  Mat3 dF = Mat3::Identity();
  dF(1, 1) = stretch;
  Mat3 s;
  for (int i = 0; i < steps; ++i)
    s = step(m, 0, dF);
  // Hughes–Winget strain increments add up to the logarithmic strain (to O(Δε^3) per step).
  const double strain = std::log(1.0 + total);
  EXPECT_NEAR(s(1, 1), kElastic.wave_modulus() * strain, 1e-9 * std::abs(s(1, 1)));
  EXPECT_NEAR(s(0, 0), kElastic.lame * strain, 1e-9 * std::abs(s(0, 0)));
  EXPECT_NEAR(s(2, 2), kElastic.lame * strain, 1e-9 * std::abs(s(0, 0)));
  EXPECT_NEAR(s(0, 0) / s(1, 1), 0.3 / 0.7, 1e-9);  // K0 = ν / (1 − ν)
  EXPECT_DOUBLE_EQ(m.wave_modulus(), kElastic.lame + 2.0 * kElastic.shear);
}

//! Largest deviation from the Jaumann closed form of simple shear to γ = 1 in `steps` steps:
//! σxy = G sin γ, σxx = −σyy = G (1 − cos γ).
double jaumann_simple_shear_error(int steps) {
  LinearElastic m(2000.0, kElastic);
  m.add_points(1);
  const double gamma = 1.0;
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = gamma / steps;
  Mat3 s;
  for (int i = 0; i < steps; ++i)
    s = step(m, 0, dF);
  const double g = kElastic.shear;
  EXPECT_NEAR(s(2, 2), 0.0, 1e-9 * g);
  return std::max({std::abs(s(0, 1) - g * std::sin(gamma)),
                   std::abs(s(0, 0) - g * (1.0 - std::cos(gamma))),
                   std::abs(s(1, 1) + g * (1.0 - std::cos(gamma)))}) /
         g;
}

TEST(LinearElastic, SimpleShearConvergesToTheJaumannClosedForm) {
  const double coarse = jaumann_simple_shear_error(2000);
  const double fine = jaumann_simple_shear_error(16000);
  EXPECT_LT(fine, 1e-4);
  EXPECT_NEAR(coarse / fine, 8.0, 0.5);  // first order in the step size
}

TEST(LinearElastic, SmallSimpleShearIsGTimesGamma) {
  LinearElastic m(2000.0, kElastic);
  m.add_points(1);
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 1e-5;
  Mat3 s;
  for (int i = 0; i < 10; ++i)
    s = step(m, 0, dF);
  EXPECT_NEAR(s(0, 1), kElastic.shear * 1e-4, 1e-7 * kElastic.shear * 1e-4);
}

TEST(LinearElastic, RigidRotationRotatesTheStressAndKeepsItsInvariants) {
  Mat3 sigma;
  sigma << -100e3, 20e3, 5e3, 20e3, -50e3, -8e3, 5e3, -8e3, -30e3;
  for (const Vec3& axis : {Vec3(0, 0, 1), Vec3(1, 2, -1)}) {
    LinearElastic m(2000.0, kElastic);
    m.add_points(3);
    m.set_stress(1, sigma);
    const int steps = 1000;
    const double quarter = 0.5 * kPi;
    const Mat3 increment = rotation(axis, quarter / steps);
    Mat3 s;
    for (int i = 0; i < steps; ++i)
      s = step(m, 1, increment);
    const Mat3 expected = rotation(axis, quarter) * sigma * rotation(axis, quarter).transpose();
    EXPECT_LT((s - expected).norm(), 1e-9 * sigma.norm()) << axis.transpose();
    EXPECT_NEAR(s.trace(), sigma.trace(), 1e-10 * sigma.norm());
    EXPECT_NEAR(s.determinant(), sigma.determinant(), 1e-9 * std::abs(sigma.determinant()));
    EXPECT_NEAR(s.squaredNorm(), sigma.squaredNorm(), 1e-10 * sigma.squaredNorm());
    EXPECT_EQ(m.stress(0), Mat3::Zero());  // other points untouched
  }
}

TEST(LinearElastic, UpdatesOnlyTheBatchItIsGivenInItsOrder) {
  LinearElastic m(2000.0, kElastic);
  EXPECT_EQ(m.add_points(2), 0u);
  EXPECT_EQ(m.add_points(3), 2u);
  Mat3 a = Mat3::Identity(), b = Mat3::Identity();
  a(0, 0) += 1e-4;
  b(1, 1) -= 1e-4;
  std::vector<Mat3> out(7, Mat3::Constant(99.0));  // resized to the batch
  m.update({{4, 1}, {a, b}, 0.1}, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_GT(out[0](0, 0), 0.0);
  EXPECT_LT(out[1](1, 1), 0.0);
  EXPECT_EQ(m.stress(4), out[0]);
  EXPECT_EQ(m.stress(1), out[1]);
  for (const std::size_t untouched : {0, 2, 3})
    EXPECT_EQ(m.stress(untouched), Mat3::Zero());
  EXPECT_THROW(m.update({{5}, {a}, 0.1}, out), std::out_of_range);
  EXPECT_THROW(m.update({{0, 1}, {a}, 0.1}, out), std::invalid_argument);
  EXPECT_THROW(m.update({{0}, {-Mat3::Identity()}, 0.1}, out), std::runtime_error);
  Mat3 flipped = Mat3::Identity();
  flipped(0, 0) = -0.5;  // det dF < 0 with dF + I regular
  EXPECT_THROW(m.update({{0}, {flipped}, 0.1}, out), std::runtime_error);
}

}  // namespace
}  // namespace mpm_lig::materials
