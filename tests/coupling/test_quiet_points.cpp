#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "core/plane_strain.h"
#include "coupling/quiet_points.h"

namespace mpm_lig::coupling {
namespace {

constexpr double kBulk = 30e6, kShear = 20e6;  // a 2D packing's secant moduli [Pa]
constexpr double kWaveModulus = kBulk + kShear;

Mat3 anchor() {
  Mat3 s = Mat3::Zero();
  s(0, 0) = -2e5;
  s(1, 1) = -1e5;
  s(2, 2) = -1.5e5;
  return s;
}

// Plane strain linear elasticity from `start`: the stress a linear soil has under `increment`.
Mat3 linear_soil(const Mat3& start, const Mat3& increment, double bulk, double shear) {
  const Mat3 e = 0.5 * (increment - Mat3::Identity() + (increment - Mat3::Identity()).transpose());
  const double ev = e(0, 0) + e(1, 1);
  Mat3 s = start;
  s(0, 0) += bulk * ev + 2.0 * shear * (e(0, 0) - 0.5 * ev);
  s(1, 1) += bulk * ev + 2.0 * shear * (e(1, 1) - 0.5 * ev);
  s(0, 1) += 2.0 * shear * e(0, 1);
  s(1, 0) += 2.0 * shear * e(1, 0);
  return s;
}

// A small compression with shear: both moduli are measurable on it.
Mat3 step(double size) {
  Mat3 dF = Mat3::Identity();
  dF(0, 0) -= 0.3 * size;
  dF(1, 1) -= size;
  dF(0, 1) += 0.5 * size;
  dF(1, 0) += 0.5 * size;
  return dF;
}

QuietSpec spec(double tolerance, double max_error, int check_every) {
  QuietSpec s;
  s.enabled = true;
  s.tolerance = tolerance;
  s.max_error = max_error;
  s.check_every = check_every;
  return s;
}

TEST(QuietPoints, PredictionIsPlaneStrainElasticity) {
  QuietPoints q;
  q.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  const Mat3 dF = step(1e-4);
  const Mat3 expected = linear_soil(anchor(), dF, kBulk, kShear);
  EXPECT_LT((q.predict(anchor(), dF, kBulk, kShear) - expected).norm(), 1e-9 * expected.norm());
}

TEST(QuietPoints, PredictionRotatesTheStressToFirstOrder) {
  QuietPoints q;
  q.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  const double angle = 1e-4;
  Mat3 rotation = Mat3::Identity();
  rotation(0, 0) = rotation(1, 1) = std::cos(angle);
  rotation(0, 1) = -std::sin(angle);
  rotation(1, 0) = std::sin(angle);
  const Mat3 exact = rotation * anchor() * rotation.transpose();
  const Mat3 predicted = q.predict(anchor(), rotation, kBulk, kShear);
  // Rigid rotation: no strain to first order, the stress turns with the grains (second-order
  // terms: angle² = 1e-8 of the stress and of the moduli).
  EXPECT_GT(std::abs(exact(0, 1)), 9.9);
  EXPECT_NEAR(predicted(0, 1), exact(0, 1), 1e-5 * anchor().norm());
  EXPECT_LT((predicted - exact).norm(), 1e-5 * anchor().norm());
  EXPECT_EQ(predicted(2, 2), anchor()(2, 2));
}

// A linear soil: once the first DEM update has measured its moduli, every prediction is the
// stress of the same point updated every step (to second order in the strain, 1e-8; before,
// the packing's starting moduli stand in).
TEST(QuietPoints, LinearSoilIsPredictedAsIfUpdatedEveryStep) {
  QuietPoints q;
  q.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  q.set_packing(0, anchor(), kWaveModulus, 0.0);
  Mat3 every_step = anchor(), total = Mat3::Identity(), dem_anchor = anchor();
  int predicted = 0;
  bool measured = false;
  for (int k = 0; k < 40; ++k) {
    const Mat3 dF = step(1.5e-5);
    every_step = linear_soil(every_step, dF, kBulk, kShear);
    total = dF * total;
    if (q.accumulate(0, dF)) {
      const Mat3 dem = linear_soil(dem_anchor, q.pending(0), kBulk, kShear);
      q.after_dem(0, dem);
      dem_anchor = dem;
      measured = true;
    } else if (measured) {
      ++predicted;
      EXPECT_LT((q.predicted(0) - every_step).norm(), 1e-5 * every_step.norm()) << "update " << k;
    }
  }
  EXPECT_GT(predicted, 20);
  EXPECT_GT(q.stats().checks, 3.0);
  EXPECT_EQ(q.tolerance(0), 1e-4);
}

// A soil that stiffens after its moduli were measured: the checks see predictions beyond the
// bound, count them and tighten the point's tolerance; once the new moduli are measured, the
// predictions are right again and the tolerance goes back to the case's.
TEST(QuietPoints, ViolatedBoundIsDetectedAndTightensTheTolerance) {
  QuietPoints q;
  q.start(1, spec(1e-4, 0.002, 50), 2, 1e3);
  q.set_packing(0, anchor(), 10 * kWaveModulus, 0.0);
  Mat3 dem_anchor = anchor();
  int dem_updates = 0;
  double tightest = 1.0;
  for (int k = 0; k < 60; ++k) {
    if (q.accumulate(0, step(1.5e-5))) {
      const double stiffer = dem_updates == 0 ? 1.0 : 4.0;
      const Mat3 dem = linear_soil(dem_anchor, q.pending(0), stiffer * kBulk, stiffer * kShear);
      q.after_dem(0, dem);
      dem_anchor = dem;
      ++dem_updates;
      tightest = std::min(tightest, q.tolerance(0));
    }
  }
  EXPECT_GT(q.stats().exceeded, 0.0);
  EXPECT_GT(q.stats().max_error, 0.002);
  EXPECT_LE(tightest, 0.5e-4);
  EXPECT_EQ(q.tolerance(0), 1e-4);
}

// sin φ = (σ1 − σ3)/(σ1 + σ3), compression positive, in the first d axes.
double sin_friction(const Mat3& stress, int d) {
  const auto [s1, s3] = extreme_principal_stresses(stress, d);
  return (s1 - s3) / (s1 + s3);
}

// The cap scales the deviator down to the limit, exactly, and keeps the mean stress, the
// principal directions and (2D) the out-of-plane stress; below the limit it changes nothing.
TEST(CappedFriction, ScalesTheDeviatorToTheLimitAndKeepsTheRest) {
  Mat3 s = anchor();
  s(0, 1) = s(1, 0) = -4e4;  // sin φ 0.43
  for (const int d : {2, 3}) {
    const double before = sin_friction(s, d);
    const Mat3 capped = capped_friction(s, 0.3, d);
    EXPECT_NEAR(sin_friction(capped, d), 0.3, 1e-12) << d;
    EXPECT_NEAR(capped.topLeftCorner(d, d).trace(), s.topLeftCorner(d, d).trace(), 1e-9) << d;
    if (d == 2)
      EXPECT_EQ(capped(2, 2), s(2, 2));
    // The same principal directions: the capped deviator is the original's multiple.
    const Mat3 mean = s.topLeftCorner(d, d).trace() / d * plane::identity_d(d);
    const Mat3 dev = plane::in_plane(s, d) - mean, dev_capped = plane::in_plane(capped, d) - mean;
    EXPECT_LT((dev_capped - dev * (dev_capped(0, 1) / dev(0, 1))).norm(), 1e-9 * dev.norm()) << d;
    EXPECT_GT(before, 0.35) << d;
    const Mat3 same = capped_friction(s, before + 0.01, d);
    EXPECT_EQ(same, s) << d;
  }
  const Mat3 tension = -s;  // not compressive: nothing to cap
  EXPECT_EQ(capped_friction(tension, 0.1, 2), tension);
}

// With cap_friction a yielding quiet point (its last DEM update did not raise its deviator along
// its shear) is predicted at no more friction than that update's answer; without the cap the
// secant it kept carries it past. A hardening point (its deviator grew) is not capped.
TEST(QuietPoints, CappedPredictionStopsAtTheLastDemFrictionOnceYielding) {
  Mat3 shear = Mat3::Identity();  // x shortens, y lengthens: the anchor's deviator grows
  shear(0, 0) = 1.0 - 2e-4;
  shear(1, 1) = 1.0 + 2e-4;
  const double at_dem = sin_friction(anchor(), 2);
  for (const bool cap : {false, true}) {
    for (const bool yielding : {false, true}) {
      QuietSpec s = spec(1e-3, 0.02, 50);  // quiet, and large enough to measure moduli on
      s.cap_friction = cap;
      QuietPoints q;
      q.start(1, s, 2, 1e3);
      q.set_packing(0, anchor(), kWaveModulus, 0.0);
      ASSERT_FALSE(q.accumulate(0, shear));
      // The DEM's answer to that increment: the same stress (yielding) or the linear soil's.
      const Mat3 dem = yielding ? anchor() : linear_soil(anchor(), shear, kBulk, kShear);
      q.after_dem(0, dem);
      ASSERT_FALSE(q.accumulate(0, shear));
      const double predicted = sin_friction(q.predicted(0), 2);
      const double last = sin_friction(dem, 2);
      if (cap && yielding)
        EXPECT_NEAR(predicted, last, 1e-12);
      else
        EXPECT_GT(predicted, last + 0.01) << cap << yielding;
    }
  }
  EXPECT_GT(at_dem, 0.3);
}

TEST(QuietPoints, CheckEveryForcesADemUpdate) {
  QuietPoints q;
  q.start(1, spec(1e-4, 0.02, 3), 2, 1e3);
  q.set_packing(0, anchor(), kWaveModulus, 0.0);
  const bool expected[] = {false, false, false, true, false};
  for (const bool must_run : expected) {
    const bool runs = q.accumulate(0, step(1e-9));
    EXPECT_EQ(runs, must_run);
    if (runs)
      q.after_dem(0, q.predicted(0));
  }
}

TEST(QuietPoints, SecantStifferThanThePackingIsNotTaken) {
  QuietPoints q;
  q.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  q.set_packing(0, anchor(), kWaveModulus, 0.0);
  const Mat3 dF = step(1e-4);
  ASSERT_TRUE(q.accumulate(0, dF));
  q.after_dem(0, linear_soil(anchor(), dF, 100 * kBulk, 100 * kShear));  // noise, not a modulus
  const Mat3 start = q.predicted(0);
  q.accumulate(0, step(1e-6));
  // Still the packing's starting pair: K = G = M / 2.
  EXPECT_LT(
      (q.predicted(0) - linear_soil(start, step(1e-6), 0.5 * kWaveModulus, 0.5 * kWaveModulus))
          .norm(),
      1e-9 * start.norm());
}

// The probe's uniaxial pair (M = K + G, L = K - G in plane strain) gives the starting moduli: a
// linear soil with K and G is predicted from its packing alone; an L that gives no stiffness
// (G <= 0) falls back to K = G = M / 2.
TEST(QuietPoints, PackingProbeGivesTheStartingModuli) {
  QuietPoints q;
  q.start(2, spec(1e-4, 0.02, 50), 2, 1e3);
  q.set_packing(0, anchor(), kBulk + kShear, kBulk - kShear);
  q.set_packing(1, anchor(), kWaveModulus, 2.0 * kWaveModulus);
  const Mat3 dF = step(5e-5);
  ASSERT_FALSE(q.accumulate(0, dF));
  ASSERT_FALSE(q.accumulate(1, dF));
  const Mat3 soil = linear_soil(anchor(), dF, kBulk, kShear);
  EXPECT_LT((q.predicted(0) - soil).norm(), 1e-9 * soil.norm());
  const Mat3 fallback = linear_soil(anchor(), dF, 0.5 * kWaveModulus, 0.5 * kWaveModulus);
  EXPECT_LT((q.predicted(1) - fallback).norm(), 1e-9 * fallback.norm());
}

// In 3D, M = K + 4G/3 and L = K - 2G/3: the probe pair gives a 3D linear soil's K and G back, and
// the fallback keeps K = G with that M (3M/7).
TEST(QuietPoints, PackingProbeGivesTheStartingModuliIn3D) {
  QuietPoints q;
  q.start(2, spec(1e-4, 0.02, 50), 3, 1e3);
  q.set_packing(0, anchor(), kBulk + 4.0 * kShear / 3.0, kBulk - 2.0 * kShear / 3.0);
  q.set_packing(1, anchor(), kWaveModulus, 2.0 * kWaveModulus);
  Mat3 dF = step(5e-5);
  dF(2, 2) -= 0.4e-5;
  ASSERT_FALSE(q.accumulate(0, dF));
  ASSERT_FALSE(q.accumulate(1, dF));
  auto soil = [&](double bulk, double shear) {
    const Mat3 e = 0.5 * (dF - Mat3::Identity() + (dF - Mat3::Identity()).transpose());
    const double ev = e.trace();
    return Mat3(anchor() + bulk * ev * Mat3::Identity() +
                2.0 * shear * (e - ev / 3.0 * Mat3::Identity()));
  };
  const Mat3 probed = soil(kBulk, kShear);
  EXPECT_LT((q.predicted(0) - probed).norm(), 1e-9 * probed.norm());
  const double equal = 3.0 * kWaveModulus / 7.0;
  const Mat3 fallback = soil(equal, equal);
  EXPECT_LT((q.predicted(1) - fallback).norm(), 1e-9 * fallback.norm());
}

TEST(QuietPoints, CheckpointRowContinuesIdentically) {
  QuietPoints a, b;
  a.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  b.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  a.set_packing(0, anchor(), kWaveModulus, 0.0);
  auto drive = [](QuietPoints& q, int k) {
    const Mat3 dF = step(1e-5 * (1 + k % 3));
    if (q.accumulate(0, dF))
      q.after_dem(0, linear_soil(q.predicted(0), Mat3::Identity(), kBulk, kShear) +
                         1e3 * (k % 2) * Mat3::Identity());
  };
  for (int k = 0; k < 17; ++k)
    drive(a, k);
  double row[QuietPoints::kValues];
  a.save_row(0, row);
  b.restore_row(0, row);
  b.restore_stats(a.stats());
  for (int k = 17; k < 40; ++k) {
    drive(a, k);
    drive(b, k);
    EXPECT_EQ((a.predicted(0) - b.predicted(0)).norm(), 0.0);
  }
  EXPECT_EQ(a.stats().predictions, b.stats().predictions);
  EXPECT_EQ(a.stats().max_error, b.stats().max_error);
  EXPECT_EQ(a.tolerance(0), b.tolerance(0));
}

ContinuumStartSpec continuum_start(double strain, double friction_deg, double max_jump) {
  ContinuumStartSpec s;
  s.enabled = true;
  s.strain = strain;
  s.friction_deg = friction_deg;
  s.max_jump = max_jump;
  return s;
}

QuietSpec quiet_off() {
  return QuietSpec{};
}

// A packing whose response is the continuum's own (K = G = M / 2): the point is continuum until
// |F - 1| passes the threshold, switches at that update, and the DEM's stress after catching up
// with the whole increment is the continuum's (no jump). Quiet points off: DEM every step after.
TEST(ContinuumStart, SwitchesAtTheStrainThresholdWithoutAJump) {
  QuietPoints q;
  q.start(1, quiet_off(), 2, 1e3, continuum_start(1e-3, 89.0, 0.05));
  q.set_packing(0, anchor(), kWaveModulus, 0.0);
  const double half = 0.5 * kWaveModulus;
  Mat3 total = Mat3::Identity();
  int switched_at = -1;
  for (int k = 0; k < 30; ++k) {
    const Mat3 dF = step(1e-4);
    total = dF * total;
    const bool runs = q.accumulate(0, dF);
    if (switched_at < 0 && !runs) {
      EXPECT_TRUE(q.is_continuum(0));
      EXPECT_LT((total - Mat3::Identity()).norm(), 1e-3) << "update " << k;
      continue;
    }
    ASSERT_TRUE(runs) << "update " << k << ": after the switch every update runs DEM";
    if (switched_at < 0) {
      switched_at = k;
      EXPECT_GE((total - Mat3::Identity()).norm(), 1e-3);
      EXPECT_LT((q.pending(0) - total).norm(), 1e-15);
    }
    q.after_dem(0, linear_soil(anchor(), total, half, half));
    EXPECT_FALSE(q.is_continuum(0));
  }
  EXPECT_GT(switched_at, 3);
  EXPECT_EQ(q.stats().switches, 1.0);
  EXPECT_EQ(q.stats().continuum_updates, static_cast<double>(switched_at));
  EXPECT_LT(q.stats().max_jump, 1e-6);  // second order in the strain
  EXPECT_EQ(q.stats().predictions, 0.0);
}

// Pure shear from an isotropic stress: the mobilised friction passes 5 degrees long before the
// strain threshold; the point switches at the first update whose predicted stress passes it.
TEST(ContinuumStart, SwitchesAtTheFrictionThreshold) {
  QuietPoints q;
  q.start(1, quiet_off(), 2, 1e3, continuum_start(0.05, 5.0, 0.05));
  const Mat3 isotropic = -1e5 * Mat3::Identity();
  q.set_packing(0, isotropic, kWaveModulus, 0.0);
  Mat3 shear = Mat3::Identity();
  shear(0, 0) += 2e-5;
  shear(1, 1) -= 2e-5;
  const double shear_modulus = 0.5 * kWaveModulus;
  int updates = 0;
  while (!q.accumulate(0, shear))
    ++updates;
  // sin φ = 2G |ε_xx - ε_yy| / 2 / p = 2 G n 2e-5 / p passes sin 5° at update n.
  const double expected = std::ceil(std::sin(5.0 * kPi / 180.0) * 1e5 / (2 * shear_modulus * 2e-5));
  EXPECT_NEAR(updates + 1, expected, 1.0);
  EXPECT_LT((q.pending(0) - Mat3::Identity()).norm(), 0.05);
}

// A packing three times stiffer than the continuum: the first switch jumps by more than the
// bound, is counted, and halves the thresholds of the points still continuum; the second point
// then switches at half the strain.
TEST(ContinuumStart, JumpAboveTheBoundIsCountedAndHalvesTheThresholds) {
  QuietPoints q;
  q.start(2, quiet_off(), 2, 1e3, continuum_start(1e-3, 89.0, 0.01));
  q.set_packing(0, anchor(), kWaveModulus, 0.0);
  q.set_packing(1, anchor(), kWaveModulus, 0.0);
  const double stiff = 1.5 * kWaveModulus;
  Mat3 total = Mat3::Identity();
  int first = -1;
  for (int k = 0; k < 12 && first < 0; ++k) {
    total = step(1e-4) * total;
    if (q.accumulate(0, step(1e-4))) {
      first = k;
      q.after_dem(0, linear_soil(anchor(), total, stiff, stiff));
    }
  }
  ASSERT_GE(first, 0);
  EXPECT_EQ(q.stats().jumps_exceeded, 1.0);
  EXPECT_GT(q.stats().max_jump, 0.01);
  EXPECT_EQ(q.stats().threshold_scale, 0.5);
  int second = -1;
  for (int k = 0; k < 12 && second < 0; ++k)
    if (q.accumulate(1, step(1e-4)))
      second = k;
  EXPECT_LT(second, first);
  EXPECT_TRUE(q.is_continuum(1));  // until its DEM update is booked
}

TEST(ContinuumStart, CheckpointRowKeepsWhetherAPointSwitched) {
  QuietPoints a, b;
  a.start(2, quiet_off(), 2, 1e3, continuum_start(1e-3, 89.0, 0.05));
  b.start(2, quiet_off(), 2, 1e3, continuum_start(1e-3, 89.0, 0.05));
  for (std::size_t p = 0; p < 2; ++p)
    a.set_packing(p, anchor(), kWaveModulus, 0.0);
  for (int k = 0; k < 12; ++k)
    if (a.accumulate(0, step(1e-4)))
      a.after_dem(0, a.predicted(0));
  a.accumulate(1, step(1e-4));
  double row[QuietPoints::kValues];
  for (std::size_t p = 0; p < 2; ++p) {
    a.save_row(p, row);
    b.restore_row(p, row);
  }
  b.restore_stats(a.stats());
  EXPECT_FALSE(b.is_continuum(0));
  EXPECT_TRUE(b.is_continuum(1));
  EXPECT_EQ(b.stats().switches, 1.0);
  EXPECT_EQ(b.stats().continuum_updates, a.stats().continuum_updates);
  EXPECT_EQ(a.accumulate(1, step(1e-4)), b.accumulate(1, step(1e-4)));
  EXPECT_EQ((a.predicted(1) - b.predicted(1)).norm(), 0.0);
}

// The mobilised friction threshold in 3D uses the largest and smallest principal stresses.
TEST(ContinuumStart, FrictionThresholdIn3D) {
  QuietPoints q;
  q.start(1, quiet_off(), 3, 1e3, continuum_start(0.05, 5.0, 0.05));
  q.set_packing(0, -1e5 * Mat3::Identity(), kWaveModulus, 0.0);
  Mat3 shear = Mat3::Identity();  // shortening along z, lengthening along x
  shear(0, 0) += 2e-5;
  shear(2, 2) -= 2e-5;
  int updates = 0;
  while (!q.accumulate(0, shear))
    ++updates;
  // L = 0 in 3D: G = M / 2. sin φ = (σ_xx - σ_zz) / 2p = 2G n 2e-5 / p passes sin 5° at update n.
  const double shear_modulus = 0.5 * kWaveModulus;
  const double expected = std::ceil(std::sin(5.0 * kPi / 180.0) * 1e5 / (2 * shear_modulus * 2e-5));
  EXPECT_NEAR(updates + 1, expected, 1.0);
  const Mat3 s = q.predicted(0);
  EXPECT_GE((s(0, 0) - s(2, 2)) / -(s(0, 0) + s(2, 2)), std::sin(5.0 * kPi / 180.0));
}

// Each statistic has its own checkpoint name and field: a name saved twice or a field restored
// from another's name would mix the statistics of a resumed run.
TEST(QuietPoints, EveryStatisticHasItsOwnCheckpointName) {
  std::set<std::string> names;
  for (const QuietStatField& f : kQuietStatFields) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
    QuietStats s;
    s.*f.value = -7.0;
    int changed = 0;
    for (const QuietStatField& g : kQuietStatFields)
      changed += (s.*g.value == -7.0);
    EXPECT_EQ(changed, 1) << f.name;
  }
}

}  // namespace
}  // namespace mpm_lig::coupling
