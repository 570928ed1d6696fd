#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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
  q.set_packing(0, anchor(), kWaveModulus);
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
  q.set_packing(0, anchor(), 10 * kWaveModulus);
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

TEST(QuietPoints, CheckEveryForcesADemUpdate) {
  QuietPoints q;
  q.start(1, spec(1e-4, 0.02, 3), 2, 1e3);
  q.set_packing(0, anchor(), kWaveModulus);
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
  q.set_packing(0, anchor(), kWaveModulus);
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

TEST(QuietPoints, CheckpointRowContinuesIdentically) {
  QuietPoints a, b;
  a.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  b.start(1, spec(1e-4, 0.02, 50), 2, 1e3);
  a.set_packing(0, anchor(), kWaveModulus);
  auto drive = [](QuietPoints& q, int k) {
    const Mat3 dF = step(1e-5 * (1 + k % 3));
    if (q.accumulate(0, dF))
      q.after_dem(0, linear_soil(q.predicted(0), Mat3::Identity(), kBulk, kShear) +
                         1e3 * (k % 2) * Mat3::Identity());
  };
  for (int k = 0; k < 17; ++k)
    drive(a, k);
  double row[QuietPoints::kValues], stats[QuietPoints::kStatValues];
  a.save_row(0, row);
  a.save_stats(stats);
  b.restore_row(0, row);
  b.restore_stats(stats);
  for (int k = 17; k < 40; ++k) {
    drive(a, k);
    drive(b, k);
    EXPECT_EQ((a.predicted(0) - b.predicted(0)).norm(), 0.0);
  }
  EXPECT_EQ(a.stats().predictions, b.stats().predictions);
  EXPECT_EQ(a.stats().max_error, b.stats().max_error);
  EXPECT_EQ(a.tolerance(0), b.tolerance(0));
}

}  // namespace
}  // namespace mpm_lig::coupling
