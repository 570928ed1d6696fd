#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "coupling/steady_flow.h"

namespace mpm_lig::coupling {
namespace {

constexpr double kStep = 0.002;  // shear strain γ of one update
constexpr double kFloor = 1e3;   // stress floor [Pa]
constexpr double kBulk = 30e6;   // the packing's bulk modulus at 100 kPa [Pa]

// A critical-state stress in simple shear: p = 100 kPa, q/p = 0.5 (shear stress on xy).
Mat3 critical_stress(double scale = 1.0) {
  Mat3 s = Mat3::Zero();
  s(0, 0) = s(1, 1) = s(2, 2) = -1e5 * scale;
  s(0, 1) = s(1, 0) = 0.5e5 * scale;
  return s;
}

// Simple shear γ along x with a volumetric strain `volumetric` (in the plane).
Mat3 shear_step(double gamma, double volumetric = 0.0) {
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = gamma;
  dF(0, 0) += 0.5 * volumetric;
  dF(1, 1) += 0.5 * volumetric;
  return dF;
}

SteadyFlowSpec spec() {
  SteadyFlowSpec s;
  s.enabled = true;
  s.window = 10 * kStep - 1e-12;  // ten updates a window
  s.check_every = 5;
  return s;
}

SteadyFlow started(const SteadyFlowSpec& s = spec()) {
  SteadyFlow f;
  f.start(1, s, 2, kFloor);
  f.set_packing(0, 1e5, kBulk);
  return f;
}

// `updates` DEM updates of point 0 under shear_step(kStep, volumetric), the stress of the k-th
// given by `stress(k)`.
template <class Stress>
void run_dem(SteadyFlow& f, int updates, Stress stress, double volumetric = 0.0) {
  for (int k = 0; k < updates; ++k)
    f.after_dem(0, shear_step(kStep, volumetric), stress(k));
}

// ±1 % noise on the shear stress, alternating: a window of ten has the exact mean.
Mat3 noisy(int k) {
  Mat3 s = critical_stress();
  s(0, 1) = s(1, 0) = 0.5e5 * (k % 2 ? 1.01 : 0.99);
  return s;
}

TEST(SteadyFlow, ReducedIncrementKeepsTheVolumeAndDropsTheShearAndTheSpin) {
  const SteadyFlow f = started();
  // A missed simple shear (stretch and spin) is dropped whole: the new increment alone.
  const Mat3 dF = shear_step(0.001);
  EXPECT_LT((f.reduced_increment(dF, shear_step(0.3)) - dF).norm(), 1e-15);
  // A missed volume change is kept as a uniform in-plane dilation, after the new increment.
  const Mat3 missed = shear_step(0.2, 0.02);
  const double j = missed.topLeftCorner(2, 2).determinant();
  Mat3 dilation = Mat3::Identity();
  dilation(0, 0) = dilation(1, 1) = std::sqrt(j);
  EXPECT_LT((f.reduced_increment(dF, missed) - dF * dilation).norm(), 1e-15);
  EXPECT_NEAR(f.reduced_increment(Mat3::Identity(), missed).topLeftCorner(2, 2).determinant(), j,
              1e-15);
}

TEST(SteadyFlow, TwoSteadyWindowsBeginAFlowAtTheWindowMean) {
  SteadyFlow f = started();
  run_dem(f, 19, noisy);
  EXPECT_FALSE(f.flowing(0));  // one window closed: nothing to compare it with
  run_dem(f, 1, [](int) { return noisy(19); });
  ASSERT_TRUE(f.flowing(0));
  EXPECT_LT((f.predicted(0) - critical_stress()).norm(), 1e-9 * critical_stress().norm());
  EXPECT_EQ(f.stats().entries, 1.0);
}

TEST(SteadyFlow, AHardeningOrDilatingPointDoesNotFlow) {
  SteadyFlow hardening = started();
  // q/p up by 2 % an update: 22 % between windows, beyond stress_change 10 %.
  run_dem(hardening, 60, [](int k) {
    Mat3 s = critical_stress();
    s(0, 1) = s(1, 0) = 0.5e5 * std::pow(1.02, k);
    return s;
  });
  EXPECT_FALSE(hardening.flowing(0));
  SteadyFlow dilating = started();
  run_dem(dilating, 60, noisy, 0.1 * kStep);  // dε_v/dγ = 0.1 > dilatancy 0.05
  EXPECT_FALSE(dilating.flowing(0));
  SteadyFlow dilated_first = started();  // the first window dilates, the second does not
  run_dem(dilated_first, 10, noisy, 0.1 * kStep);
  run_dem(dilated_first, 10, noisy);
  EXPECT_FALSE(dilated_first.flowing(0));
  run_dem(dilated_first, 10, noisy);  // now both windows hold their volume
  EXPECT_TRUE(dilated_first.flowing(0));
  SteadyFlow unloaded = started();  // p below the stress floor: no flow recognised
  run_dem(unloaded, 60, [](int) { return critical_stress(1e-3); });
  EXPECT_FALSE(unloaded.flowing(0));
  EXPECT_EQ(hardening.stats().entries + dilating.stats().entries + unloaded.stats().entries, 0.0);
}

TEST(SteadyFlow, AFlowingPointIsPredictedAndCheckedEveryCheckEvery) {
  SteadyFlow f = started();
  run_dem(f, 20, noisy);
  ASSERT_TRUE(f.flowing(0));
  for (int k = 0; k < 5; ++k)
    EXPECT_FALSE(f.accumulate(0, shear_step(kStep))) << k;
  EXPECT_NEAR(f.stats().skipped_shear, 5 * kStep, 1e-12);
  ASSERT_TRUE(f.accumulate(0, shear_step(kStep)));  // the check
  // The RVE runs this update's increment and the volume change it missed, not the shear.
  const Mat3 missed = shear_step(kStep) * shear_step(kStep) * shear_step(kStep) *
                      shear_step(kStep) * shear_step(kStep);
  EXPECT_LT((f.catch_up(0) - f.reduced_increment(shear_step(kStep), missed)).norm(), 1e-14);
  // A steady simple shear's stress is constant in space: the prediction is the window mean.
  EXPECT_LT((f.predicted(0) - critical_stress()).norm(), 1e-9 * critical_stress().norm());
  f.after_dem(0, f.catch_up(0), critical_stress(1.02));
  EXPECT_TRUE(f.flowing(0));
  EXPECT_EQ(f.stats().checks, 1.0);
  EXPECT_NEAR(f.stats().max_error, 0.02 / 1.02, 1e-12);
  // The check's stress joins the mean of two samples.
  EXPECT_LT((f.predicted(0) - critical_stress(1.01)).norm(), 1e-9 * critical_stress().norm());
  EXPECT_FALSE(f.accumulate(0, shear_step(kStep)));  // flowing on
}

TEST(SteadyFlow, AFlowingPointResistsAVolumeChangeWithThePackingsBulkModulus) {
  SteadyFlow f = started();
  run_dem(f, 20, noisy);
  ASSERT_TRUE(f.flowing(0));
  // Compression ε_v = -1e-4 at p = p0: Δσ = K ε_v on both in-plane axes, none out of plane.
  EXPECT_FALSE(f.accumulate(0, shear_step(kStep, -1e-4)));
  const Mat3 change = f.predicted(0) - critical_stress();
  EXPECT_NEAR(change(0, 0), -kBulk * 1e-4, 1e-6);
  EXPECT_NEAR(change(1, 1), -kBulk * 1e-4, 1e-6);
  EXPECT_NEAR(change(2, 2), 0.0, 1e-9);
  EXPECT_NEAR(change(0, 1), 0.0, 1e-9);
  // At four times the pressure the packing is twice as stiff (√(p/p0)).
  SteadyFlow deep = started();
  run_dem(deep, 20, [](int k) { return Mat3(4.0 * noisy(k)); });
  ASSERT_TRUE(deep.flowing(0));
  deep.accumulate(0, shear_step(kStep, -1e-4));
  EXPECT_NEAR((deep.predicted(0) - critical_stress(4.0))(0, 0), -2.0 * kBulk * 1e-4, 1e-6);
}

TEST(SteadyFlow, AWindowOfChecksThatDriftsEndsTheFlow) {
  SteadyFlow f = started();
  run_dem(f, 20, noisy);
  ASSERT_TRUE(f.flowing(0));
  // Checks 8 % above the flow each (below max_error), then 25 % (a drift, still below it):
  // the first window of checks is steady and goes on, the second is not.
  int checks = 0;
  for (int update = 0; update < 2 * 6 * 10 && f.flowing(0); ++update) {
    if (f.accumulate(0, shear_step(kStep))) {
      f.after_dem(0, f.catch_up(0), critical_stress(checks < 10 ? 1.08 : 1.08 * 1.12));
      ++checks;
    }
  }
  EXPECT_EQ(checks, 20);
  EXPECT_FALSE(f.flowing(0));
  EXPECT_EQ(f.stats().drifts, 1.0);
  EXPECT_EQ(f.stats().exceeded, 0.0);
}

TEST(SteadyFlow, ASlowDriftEndsTheFlowOnceItAddsUpSinceTheFlowBegan) {
  SteadyFlow f = started();
  run_dem(f, 20, noisy);
  ASSERT_TRUE(f.flowing(0));
  // Each window of checks 6 % above the one before (below stress_change 10 %): the second
  // window is 12 % above the flow's first and ends it.
  int windows = 0, checks = 0;
  for (int update = 0; update < 4 * 6 * 10 && f.flowing(0); ++update) {
    if (f.accumulate(0, shear_step(kStep))) {
      f.after_dem(0, f.catch_up(0), critical_stress(std::pow(1.06, 1 + checks / 10)));
      windows = ++checks / 10;
    }
  }
  EXPECT_FALSE(f.flowing(0));
  EXPECT_EQ(windows, 2);
  EXPECT_EQ(f.stats().drifts, 1.0);
}

TEST(SteadyFlow, ATurnAVolumeChangeOrAFailedCheckEndsTheFlow) {
  SteadyFlow turned = started();
  run_dem(turned, 20, noisy);
  EXPECT_TRUE(turned.accumulate(0, shear_step(-kStep)));  // reversed shear
  EXPECT_FALSE(turned.flowing(0));
  EXPECT_EQ(turned.stats().turns, 1.0);
  // A tiny increment tells no direction: it does not end a flow.
  SteadyFlow paused = started();
  run_dem(paused, 20, noisy);
  EXPECT_FALSE(paused.accumulate(0, shear_step(-0.1 * kStep)));

  // One increment off the path after several along it does not turn the path since the last
  // DEM update (their sum): the flow goes on.
  SteadyFlow steady = started();
  run_dem(steady, 20, noisy);
  for (int k = 0; k < 3; ++k)
    EXPECT_FALSE(steady.accumulate(0, shear_step(kStep)));
  EXPECT_FALSE(steady.accumulate(0, shear_step(-kStep)));
  EXPECT_EQ(steady.stats().turns, 0.0);

  SteadyFlow compressed = started();
  run_dem(compressed, 20, noisy);
  EXPECT_FALSE(compressed.accumulate(0, shear_step(kStep, -1.5e-3)));
  EXPECT_TRUE(compressed.accumulate(0, shear_step(kStep, -1.5e-3)));  // 3e-3 > 2e-3
  EXPECT_EQ(compressed.stats().volume_exits, 1.0);
  EXPECT_FALSE(compressed.flowing(0));

  SteadyFlow failed = started();
  run_dem(failed, 20, noisy);
  for (int k = 0; k < 5; ++k)
    failed.accumulate(0, shear_step(kStep));
  ASSERT_TRUE(failed.accumulate(0, shear_step(kStep)));
  failed.after_dem(0, failed.catch_up(0), critical_stress(0.7));  // 30 % off, above 15 %
  EXPECT_FALSE(failed.flowing(0));
  EXPECT_EQ(failed.stats().exceeded, 1.0);
  // After an end the point needs two new steady windows.
  run_dem(failed, 19, noisy);
  EXPECT_FALSE(failed.flowing(0));
  run_dem(failed, 1, noisy);
  EXPECT_TRUE(failed.flowing(0));
}

TEST(SteadyFlow, ACheckpointRowContinuesTheSameWay) {
  // Saved mid-window (13 of the 20 updates that begin a flow), then run past the window's
  // close, the flow's begin, its checks and a window of checks.
  SteadyFlow f = started();
  run_dem(f, 13, noisy);
  std::vector<double> row(SteadyFlow::kValues);
  f.save_row(0, row.data());
  SteadyFlow g = started();
  g.restore_row(0, row.data());
  g.restore_stats(f.stats());
  for (int k = 13; k < 20; ++k) {
    f.after_dem(0, shear_step(kStep), noisy(k));
    g.after_dem(0, shear_step(kStep), noisy(k));
  }
  ASSERT_TRUE(f.flowing(0));
  ASSERT_TRUE(g.flowing(0));
  for (int k = 0; k < 80; ++k) {
    const Mat3 dF = shear_step(kStep * (1.0 + 0.01 * (k % 3)));
    const bool runs = f.accumulate(0, dF);
    ASSERT_EQ(runs, g.accumulate(0, dF)) << k;
    if (runs) {
      EXPECT_EQ(f.catch_up(0), g.catch_up(0));
      f.after_dem(0, f.catch_up(0), critical_stress(1.0 + 0.003 * (k % 5)));
      g.after_dem(0, g.catch_up(0), critical_stress(1.0 + 0.003 * (k % 5)));
    }
    ASSERT_EQ(f.predicted(0), g.predicted(0)) << k;
  }
  EXPECT_EQ(f.stats().checks, g.stats().checks);
  EXPECT_GE(f.stats().checks, 10.0);  // a whole window of checks ran after the restore
  EXPECT_EQ(f.stats().skipped_shear, g.stats().skipped_shear);
  std::vector<double> again(SteadyFlow::kValues), other(SteadyFlow::kValues);
  f.save_row(0, again.data());
  g.save_row(0, other.data());
  EXPECT_EQ(again, other);
}

}  // namespace
}  // namespace mpm_lig::coupling
