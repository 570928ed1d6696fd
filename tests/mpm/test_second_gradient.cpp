// The second-gradient energy of an internal length: its force tensors are the derivative of
// its energy (a finite-difference check along random velocity gradients), it is zero for a
// uniform F, and a rigid rotation of the whole body leaves the energy as it was and turns the
// force tensors with it (objectivity), and the energy does not change when the points move at
// fixed F (the forces are its derivative in F only, so anything else it depended on would do
// work no force accounts for); through volumetric smoothing's work-conjugate the forces still
// do the work the energy's change accounts for. The fitted gradient is blind to a strain
// alternating from point to point; the fit's residual energy sees it, and adds nothing to a
// linear F.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mpm/second_gradient.h"
#include "mpm/volumetric_smoothing.h"
#include "support.h"

namespace mpm_lig::mpm {
namespace {

using testing::plane_rotation;

using Vec2 = Eigen::Vector2d;
using Matrix = Eigen::Matrix2d;

//! A point at rest at x with volume v and deformation f.
void add_point(Particles<2>& particles, const Vec2& x, double v, const Mat3& f) {
  particles.position.push_back(x);
  particles.reference.push_back(x);
  particles.volume.push_back(v);
  particles.volume0.push_back(v);
  particles.deformation.push_back(f);
}

//! Points on a 6 x 5 lattice (spacing 0.05) of a grid of 0.1 cells, F varying smoothly
//! across them plus a little noise, so every point has a different gradient.
Particles<2> lattice(std::mt19937& random) {
  std::uniform_real_distribution<double> noise(-0.01, 0.01);
  Particles<2> particles;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 5; ++j) {
      const Vec2 x(0.025 + 0.05 * i, 0.025 + 0.05 * j);
      const double v = 0.0025 * (1.0 + noise(random));
      Mat3 f = Mat3::Identity();
      f(0, 0) += 0.1 * x[1] * x[1] + noise(random);
      f(0, 1) += 0.3 * x[1] + noise(random);
      f(1, 0) += noise(random);
      f(1, 1) -= 0.05 * x[0] + noise(random);
      add_point(particles, x, v, f);
    }
  }
  return particles;
}

const Grid<2> kGrid(Vec2(0.0, 0.0), Vec2(0.3, 0.3), {3, 3});

TEST(SecondGradient, ModulusGivesTheBandWidthAsFullWidthAtHalfHeight) {
  // ℓ = π √(D / G_s).
  const double d = SecondGradient<2>::modulus(0.1, 4e5);
  EXPECT_NEAR(std::acos(-1.0) * std::sqrt(d / 4e5), 0.1, 1e-15);
}

//! Along F_p ← (I + ε L_p) F_p, random L, `energy` changes by ε Σ_p S_p : L_p to first order.
void expect_forces_are_the_derivative(const SecondGradient<2>& energy,
                                      const Particles<2>& particles, std::mt19937& random) {
  std::vector<Matrix> s;
  energy.force_tensors(particles, kGrid, s);
  ASSERT_EQ(s.size(), particles.size());
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<Matrix> l(particles.size());
    double predicted = 0.0;
    for (std::size_t p = 0; p < particles.size(); ++p) {
      l[p] << normal(random), normal(random), normal(random), normal(random);
      predicted += (s[p].array() * l[p].array()).sum();
    }
    auto moved = [&](double eps) {
      Particles<2> m = particles;
      for (std::size_t p = 0; p < m.size(); ++p) {
        Mat3 step = Mat3::Identity();
        step.topLeftCorner<2, 2>() += eps * l[p];
        m.deformation[p] = step * m.deformation[p];
      }
      return energy.energy(m, kGrid);
    };
    const double eps = 1e-6;
    const double measured = (moved(eps) - moved(-eps)) / (2.0 * eps);
    EXPECT_NEAR(measured, predicted, 1e-6 * std::abs(predicted)) << trial;
    EXPECT_GT(std::abs(predicted), 0.0);
  }
}

//! The body turned rigidly (F → Q F, positions about the centre) keeps `energy`'s energy and
//! turns its force tensors: S → Q S Qᵀ.
void expect_rotation_changes_nothing(const SecondGradient<2>& energy,
                                     const Particles<2>& particles) {
  Particles<2> turned = particles;
  const Mat3 q = plane_rotation(1.1);
  for (std::size_t p = 0; p < turned.size(); ++p) {
    turned.deformation[p] = q * turned.deformation[p];
    turned.position[p] =
        Vec2(0.15, 0.15) + q.topLeftCorner<2, 2>() * (turned.position[p] - Vec2(0.15, 0.15));
  }
  const double e = energy.energy(particles, kGrid);
  EXPECT_GT(e, 0.0);
  EXPECT_NEAR(energy.energy(turned, kGrid), e, 1e-12 * e);
  std::vector<Matrix> s, s_turned;
  energy.force_tensors(particles, kGrid, s);
  energy.force_tensors(turned, kGrid, s_turned);
  const Matrix q2 = q.topLeftCorner<2, 2>();
  for (std::size_t p = 0; p < s.size(); ++p)
    EXPECT_NEAR((s_turned[p] - q2 * s[p] * q2.transpose()).norm(), 0.0, 1e-9 * s[p].norm() + 1e-20)
        << p;
}

TEST(SecondGradient, ForceTensorsAreTheEnergysDerivative) {
  std::mt19937 random(7);
  const Particles<2> particles = lattice(random);
  expect_forces_are_the_derivative(SecondGradient<2>(0.1, 1e6), particles, random);
}

TEST(SecondGradient, UniformDeformationHasNoEnergyAndNoForce) {
  std::mt19937 random(3);
  Particles<2> particles = lattice(random);
  for (Mat3& f : particles.deformation)
    f = plane_rotation(0.4) * (Mat3() << 1.1, 0.2, 0.0, -0.05, 0.93, 0.0, 0.0, 0.0, 1.0).finished();
  const SecondGradient<2> energy(0.1, 1e6);
  EXPECT_EQ(energy.energy(particles, kGrid), 0.0);
  std::vector<Matrix> s;
  energy.force_tensors(particles, kGrid, s);
  for (const Matrix& sp : s)
    EXPECT_EQ(sp.norm(), 0.0);
}

TEST(SecondGradient, RigidRotationKeepsTheEnergyAndTurnsTheForces) {
  std::mt19937 random(11);
  expect_rotation_changes_nothing(SecondGradient<2>(0.1, 1e6), lattice(random));
}

//! A bounded second gradient on the lattice, relaxed once at the yield gradient `yield`
//! (the lattice's gradients are about 0.3 per metre).
SecondGradient<2> relaxed_once(const Particles<2>& particles, double yield) {
  SecondGradient<2> energy(0.1, 1e6, yield);
  energy.relax(particles, kGrid);
  return energy;
}

// Relaxing returns every point whose gradient exceeds the yield to the yield: the energy is at
// most ½ D κ² Σ V⁰ and what it gave up is booked as dissipated, exactly; a yield above every
// gradient relaxes nothing (the unbounded energy and forces, bit for bit).
TEST(SecondGradient, RelaxingBoundsTheEnergyAndBooksWhatItGaveUp) {
  std::mt19937 random(5);
  const Particles<2> particles = lattice(random);
  const SecondGradient<2> unbounded(0.1, 1e6);
  const double before = unbounded.energy(particles, kGrid);
  const double yield = 0.1;
  const SecondGradient<2> bounded = relaxed_once(particles, yield);
  double volume = 0.0;
  for (const double v : particles.volume0)
    volume += v;
  const double after = bounded.energy(particles, kGrid);
  EXPECT_LE(after, 0.5 * unbounded.modulus() * yield * yield * volume * (1.0 + 1e-12));
  EXPECT_GT(bounded.dissipated(), 0.1 * before);
  EXPECT_NEAR(after + bounded.dissipated(), before, 1e-12 * before);
  const SecondGradient<2> loose = relaxed_once(particles, 1e3);
  EXPECT_EQ(loose.dissipated(), 0.0);
  EXPECT_EQ(loose.energy(particles, kGrid), before);
  std::vector<Matrix> s, s_loose;
  unbounded.force_tensors(particles, kGrid, s);
  loose.force_tensors(particles, kGrid, s_loose);
  for (std::size_t p = 0; p < s.size(); ++p)
    EXPECT_EQ((s[p] - s_loose[p]).norm(), 0.0) << p;
}

// With a relaxed part the forces are still the energy's derivative (its rotation's share
// included), and a rigid rotation changes nothing: the relaxed part turns with the points.
TEST(SecondGradient, RelaxedForcesAreTheEnergysDerivativeAndObjective) {
  std::mt19937 random(9);
  const Particles<2> particles = lattice(random);
  const SecondGradient<2> bounded = relaxed_once(particles, 0.1);
  ASSERT_GT(bounded.dissipated(), 0.0);
  // Away from the state it was relaxed in, so that the relaxed part is not parallel to r.
  Particles<2> later = particles;
  for (std::size_t p = 0; p < later.size(); ++p)
    later.deformation[p] = plane_rotation(0.2 * later.position[p][0]) * later.deformation[p];
  expect_forces_are_the_derivative(bounded, later, random);
  expect_rotation_changes_nothing(bounded, later);
}

// A checkpoint's record of the relaxed part gives another instance the same energy, forces and
// dissipation, bit for bit.
TEST(SecondGradient, RelaxationStateRoundTrips) {
  std::mt19937 random(13);
  const Particles<2> particles = lattice(random);
  const SecondGradient<2> bounded = relaxed_once(particles, 0.1);
  SecondGradient<2> restored(0.1, 1e6, 0.1);
  restored.restore_relaxation(bounded.relaxation_state(particles.size()), particles.size());
  EXPECT_EQ(restored.dissipated(), bounded.dissipated());
  EXPECT_EQ(restored.energy(particles, kGrid), bounded.energy(particles, kGrid));
  std::vector<Matrix> s, s_restored;
  bounded.force_tensors(particles, kGrid, s);
  restored.force_tensors(particles, kGrid, s_restored);
  for (std::size_t p = 0; p < s.size(); ++p)
    EXPECT_EQ((s[p] - s_restored[p]).norm(), 0.0) << p;
  EXPECT_THROW(restored.restore_relaxation({1.0, 2.0}, particles.size()), std::runtime_error);
  // Written before any point yielded: the unbounded arithmetic, bit for bit, after the resume.
  SecondGradient<2> before_yield(0.1, 1e6, 1e3), resumed(0.1, 1e6, 1e3);
  before_yield.relax(particles, kGrid);
  resumed.restore_relaxation(before_yield.relaxation_state(particles.size()), particles.size());
  std::vector<Matrix> s_before, s_resumed;
  before_yield.force_tensors(particles, kGrid, s_before);
  resumed.force_tensors(particles, kGrid, s_resumed);
  for (std::size_t p = 0; p < s.size(); ++p)
    EXPECT_EQ((s_before[p] - s_resumed[p]).norm(), 0.0) << p;
}

TEST(SecondGradient, MovingThePointsAtFixedDeformationDoesNoWork) {
  // Neighbours closing in (a band sheared past its neighbours, points crowding under a
  // footing) and volumes changing at fixed F: the energy must stay what it was.
  std::mt19937 random(5);
  const Particles<2> particles = lattice(random);
  Particles<2> moved = particles;
  std::uniform_real_distribution<double> shift(-0.02, 0.02);
  for (std::size_t p = 0; p < moved.size(); ++p) {
    moved.position[p] += Vec2(shift(random) + 0.3 * (moved.position[p][1] - 0.15), shift(random));
    moved.volume[p] *= 0.8;
  }
  const SecondGradient<2> energy(0.1, 1e6);
  const double e = energy.energy(particles, kGrid);
  EXPECT_GT(e, 0.0);
  EXPECT_EQ(energy.energy(moved, kGrid), e);
  std::vector<Matrix> s, s_moved;
  energy.force_tensors(particles, kGrid, s);
  energy.force_tensors(moved, kGrid, s_moved);
  for (std::size_t p = 0; p < s.size(); ++p)
    EXPECT_EQ(s_moved[p], s[p]) << p;
}

TEST(SecondGradient, NeighboursAreBuiltAgainForAnotherReference) {
  // The lists are kept between calls: a new reference configuration (the main stage's start,
  // a resume) must give what a fresh object gives, and the old one its old answer again.
  std::mt19937 random(17);
  const Particles<2> first = lattice(random);
  Particles<2> second = first;
  for (Vec2& x : second.reference)
    x = Vec2(0.15, 0.15) + Vec2(0.9 * (x[0] - 0.15), 0.7 * (x[1] - 0.15));
  const SecondGradient<2> kept(0.1, 1e6);
  const double e_first = kept.energy(first, kGrid);
  const double e_second = kept.energy(second, kGrid);
  EXPECT_NE(e_second, e_first);
  EXPECT_EQ(e_second, SecondGradient<2>(0.1, 1e6).energy(second, kGrid));
  EXPECT_EQ(kept.energy(first, kGrid), e_first);
}

TEST(SecondGradient, ForcesThroughTheSmoothingsConjugateDoTheEnergysWork) {
  // The rates L_p become L̃_p once the smoothing has evened the volume change over each cell
  // (four points a cell here): the energy then changes by ε Σ S_p : L̃_p, which the pulled-back
  // tensors give as ε Σ S̃_p : L_p; the tensors as they were miss it.
  std::mt19937 random(13);
  const Particles<2> particles = lattice(random);
  const SecondGradient<2> energy(0.1, 1e6);
  const VolumetricSmoothing<2> smoothing;
  const KinematicsContext<2> context{particles, kGrid, 1.0};
  std::vector<Matrix> s;
  energy.force_tensors(particles, kGrid, s);
  std::vector<Matrix> pulled = s;
  smoothing.pull_back(context, pulled);
  std::normal_distribution<double> normal;
  std::vector<Matrix> l(particles.size());
  double predicted = 0.0, unpulled = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    l[p] << normal(random), normal(random), normal(random), normal(random);
    predicted += (pulled[p].array() * l[p].array()).sum();
    unpulled += (s[p].array() * l[p].array()).sum();
  }
  auto smoothed = [&](double eps) {
    std::vector<Mat3> increments(particles.size(), Mat3::Identity());
    for (std::size_t p = 0; p < particles.size(); ++p)
      increments[p].topLeftCorner<2, 2>() += eps * l[p];
    smoothing.apply(context, increments);
    Particles<2> m = particles;
    for (std::size_t p = 0; p < m.size(); ++p)
      m.deformation[p] = increments[p] * m.deformation[p];
    return energy.energy(m, kGrid);
  };
  const double eps = 1e-6;
  const double measured = (smoothed(eps) - smoothed(-eps)) / (2.0 * eps);
  EXPECT_NEAR(measured, predicted, 1e-5 * std::abs(predicted));
  EXPECT_GT(std::abs(unpulled - measured), 0.01 * std::abs(measured));
}

//! One point at the centre of every cell (h = 0.05) of a grid periodic along x and y, so every
//! point has the same eight neighbours; F = I + sign(i, j) A.
Particles<2> periodic_lattice(const Matrix& a, int (*sign)(int, int)) {
  Particles<2> particles;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      Mat3 f = Mat3::Identity();
      f.topLeftCorner<2, 2>() += sign(i, j) * a;
      add_point(particles, Vec2(0.025 + 0.05 * i, 0.025 + 0.05 * j), 0.0025, f);
    }
  }
  return particles;
}

const Grid<2> kPeriodicGrid(Vec2(0.0, 0.0), Vec2(0.4, 0.4), {8, 8}, {true, true});

TEST(SecondGradient, TheFitIsBlindToAlternationAndTheResidualSeesIt) {
  // Neighbours within 1.5 h: four at h (weight 1 − 1/2.25 = 5/9), four at √2 h (1/9). Alternate
  // columns differ by 2A from the two neighbours along x and the four diagonal ones:
  // Σ ŵ |r|²/|dX|² = (2·5/9·4 + 4·1/9·4/2) / (8/3) |A|²/h² = 2 |A|²/h²; a checkerboard differs
  // from the four at h: (4·5/9·4) / (8/3) = 10/3 |A|²/h². E_r = ½ D β V⁰ that a point.
  Matrix a;
  a << 0.002, 0.01, 0.004, -0.003;
  const double h = 0.05, volume = 0.0025, beta = 1.5, points = 64.0;
  const SecondGradient<2> fitted(0.1, 1e6), residual(0.1, 1e6, 0.0, beta);
  const double d = fitted.modulus();
  struct Pattern {
    int (*sign)(int, int);
    double sum;
  };
  const Pattern patterns[] = {{[](int i, int) { return i % 2 ? 1 : -1; }, 2.0},
                              {[](int i, int j) { return (i + j) % 2 ? 1 : -1; }, 10.0 / 3.0}};
  for (const Pattern& pattern : patterns) {
    const Particles<2> particles = periodic_lattice(a, pattern.sign);
    const double expected =
        points * 0.5 * d * beta * volume * pattern.sum * a.squaredNorm() / (h * h);
    EXPECT_NEAR(fitted.energy(particles, kPeriodicGrid), 0.0, 1e-12 * expected);
    EXPECT_NEAR(residual.energy(particles, kPeriodicGrid), expected, 1e-10 * expected);
    std::vector<Matrix> s;
    fitted.force_tensors(particles, kPeriodicGrid, s);
    for (const Matrix& sp : s)
      EXPECT_NEAR(sp.norm(), 0.0, 1e-9);
  }
}

TEST(SecondGradient, TheResidualAddsNothingToALinearDeformation) {
  std::mt19937 random(5);
  Particles<2> particles = lattice(random);
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const Vec2 x = particles.reference[p];
    particles.deformation[p] = Mat3::Identity();
    particles.deformation[p](0, 1) += 0.3 * x[1] - 0.1 * x[0];
    particles.deformation[p](1, 1) += 0.2 * x[0];
  }
  const double e = SecondGradient<2>(0.1, 1e6).energy(particles, kGrid);
  EXPECT_GT(e, 0.0);
  EXPECT_NEAR(SecondGradient<2>(0.1, 1e6, 0.0, 2.0).energy(particles, kGrid), e, 1e-10 * e);
}

TEST(SecondGradient, WithTheResidualForcesAreTheEnergysDerivativeAndObjective) {
  std::mt19937 random(13);
  const Particles<2> particles = lattice(random);
  const SecondGradient<2> energy(0.1, 1e6, 0.0, 1.0);
  EXPECT_GT(energy.energy(particles, kGrid), SecondGradient<2>(0.1, 1e6).energy(particles, kGrid));
  expect_forces_are_the_derivative(energy, particles, random);
  expect_rotation_changes_nothing(energy, particles);
  SecondGradient<2> bounded(0.1, 1e6, 0.1, 1.0);
  bounded.relax(particles, kGrid);
  expect_forces_are_the_derivative(bounded, particles, random);
  EXPECT_THROW(SecondGradient<2>(0.1, 1e6, 0.0, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace mpm_lig::mpm
