// The balancer's plans and the stepping totals against loads worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>

#include "coupling/rve_balance.h"

using mpm_lig::coupling::BalancePlan;
using mpm_lig::coupling::group_loads;
using mpm_lig::coupling::GroupSpeed;
using mpm_lig::coupling::lpt_owners;
using mpm_lig::coupling::plan_moves;
using mpm_lig::coupling::StepTotals;

namespace {

double makespan(const std::vector<double>& cost, const std::vector<int>& owner, int groups) {
  const std::vector<double> load = group_loads(cost, owner, groups);
  return *std::max_element(load.begin(), load.end());
}

}  // namespace

TEST(RveBalance, MovesThePointClosestToHalfTheDifference) {
  // Group 0 carries 10 + 1 + 8 = 19, group 1 carries 3: moving the 8 evens them at 11.
  const std::vector<double> cost{10, 1, 1, 1, 8, 1};
  const std::vector<int> owner{0, 1, 0, 1, 0, 1};
  const BalancePlan plan = plan_moves(cost, owner, 2, 0.0, 1, 0.0);
  EXPECT_EQ(plan.moves, 1u);
  EXPECT_EQ(plan.makespan_before, 19.0);
  EXPECT_EQ(plan.makespan_after, 11.0);
  std::vector<int> expected = owner;
  expected[4] = 1;
  EXPECT_EQ(plan.owner, expected);
  EXPECT_EQ(makespan(cost, plan.owner, 2), plan.makespan_after);
}

TEST(RveBalance, ASlowerGroupGetsLessWork) {
  // Work 4 + 2 + 2 on each of two groups, group 1 taking 1.5× as long per unit of work
  // (factors 0.8 and 1.2): predicted times 6.4 and 9.6. Moving one 2 from group 1 to 0 gives
  // 8.0 and 7.2; the 4 would make group 0 the busier one (4 × 0.8 is the whole difference).
  const std::vector<double> cost{4, 4, 2, 2, 2, 2};
  const std::vector<int> owner{0, 1, 0, 1, 0, 1};
  const std::vector<double> slow{0.8, 1.2};  // ratio 1.5, mean 1
  const BalancePlan plan = plan_moves(cost, owner, 2, 0.0, 1, 0.0, slow);
  EXPECT_DOUBLE_EQ(plan.makespan_before, 9.6);
  EXPECT_EQ(plan.moves, 1u);
  const std::vector<double> load = group_loads(cost, plan.owner, 2);
  EXPECT_EQ(load[0], 10.0);
  EXPECT_EQ(load[1], 6.0);
  EXPECT_DOUBLE_EQ(plan.makespan_after, 8.0);
  // Equal speeds: already balanced, nothing moves; explicit ones plan as the default does.
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 1, 0.0).moves, 0u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 1, 0.0, {1.0, 1.0}).moves, 0u);
  // Within the threshold of the ideal time Σ cost / Σ 1/slowness = 16 / 2.0833 = 7.68: 9.6 is
  // 25 % above it.
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.24, 1, 0.0, slow).moves, 1u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.26, 1, 0.0, slow).moves, 0u);
}

TEST(RveBalance, APeakThatPassesDoesNotPayForPilingPointsOnOneGroup) {
  // Group 0: a peak A (cost 10, floor 2) and B (2); group 1: C and D (2 each). Moving B evens
  // the coming update (12 → 10) but leaves 1 point against 3 once the peak has passed.
  const std::vector<double> cost{10, 2, 2, 2};
  const std::vector<double> floor{2, 2, 2, 2};
  const std::vector<int> owner{0, 0, 1, 1};
  // Persistence 1: the gain of 2 counts ten times.
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 10, 0.0, {}, floor, 1.0).moves, 1u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 10, 0.0).moves, 1u);  // no floor: the same
  // Persistence 0.6: update k's peak is 2 + 8 × 0.6^k; the gains 2, 2, 0.88, then below zero
  // (the floor alone: 4 → 6): over 10 updates the move loses, over 3 it gains 4.88.
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 10, 0.0, {}, floor, 0.6).moves, 0u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 3, 4.8, {}, floor, 0.6).moves, 1u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 3, 4.9, {}, floor, 0.6).moves, 0u);
  // Persistence 0: the coming update once, then the floor nine times.
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 10, 0.0, {}, floor, 0.0).moves, 0u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 1, 0.0, {}, floor, 0.0).moves, 1u);
}

TEST(RveBalance, GroupSpeedIsSmoothedSecondsPerWorkOverTheMean) {
  GroupSpeed speed(3);
  EXPECT_EQ(speed.slowness(), (std::vector<double>{1.0, 1.0, 1.0}));
  // Group 0: 2 s for 4 units; group 1: 3 s for 2 units; group 2 ran nothing.
  const std::vector<int> owner{0, 0, 1, 2};
  speed.observe({1, 3, 2, 0}, {0.5, 1.5, 3.0, 0.0}, owner);
  std::vector<double> s = speed.slowness();
  EXPECT_DOUBLE_EQ(s[0], 0.5 / 1.0);  // 0.5 s per unit over the measured mean (0.5 + 1.5) / 2
  EXPECT_DOUBLE_EQ(s[1], 1.5 / 1.0);
  EXPECT_EQ(s[2], 1.0);
  // A second update with group 0 at 1.5 s per unit: 0.8 × 0.5 + 0.2 × 1.5 = 0.7.
  speed.observe({1, 1, 0, 0}, {1.5, 1.5, 0.0, 0.0}, owner);
  s = speed.slowness();
  EXPECT_DOUBLE_EQ(s[0], 0.7 / 1.1);
  EXPECT_DOUBLE_EQ(s[1], 1.5 / 1.1);
}

TEST(RveBalance, MovesOnlyWhenTheGainPaysAndTheImbalanceIsAboveTheThreshold) {
  const std::vector<double> cost{10, 1, 1, 1, 8, 1};
  const std::vector<int> owner{0, 1, 0, 1, 0, 1};
  // Gain 19 - 11 = 8 per update: over 2 updates 16 > 15, not > 16.
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 2, 15.0).moves, 1u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.0, 2, 16.0).moves, 0u);
  // max/mean - 1 = 19 / 11 - 1 = 0.727.
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.72, 1, 0.0).moves, 1u);
  EXPECT_EQ(plan_moves(cost, owner, 2, 0.73, 1, 0.0).moves, 0u);
  EXPECT_EQ(plan_moves(cost, owner, 1, 0.0, 1, 0.0).moves, 0u);
  EXPECT_EQ(plan_moves(std::vector<double>(6, 0.0), owner, 2, 0.0, 1, 0.0).moves, 0u);
}

TEST(RveBalance, TiedBusiestGroupsAreBothRelieved) {
  // Groups 0 and 1 at 6, group 2 empty: one move gains nothing, two reach 4, 4, 4.
  const std::vector<double> cost{4, 4, 2, 2};
  const std::vector<int> owner{0, 1, 0, 1};
  const BalancePlan plan = plan_moves(cost, owner, 3, 0.0, 1, 0.5);
  EXPECT_EQ(plan.moves, 2u);
  EXPECT_EQ(plan.makespan_after, 4.0);
  EXPECT_EQ(makespan(cost, plan.owner, 3), 4.0);
  // At a move cost of 1 per point the two moves gain 2 - 2 = 0: none.
  EXPECT_EQ(plan_moves(cost, owner, 3, 0.0, 1, 1.0).moves, 0u);
}

TEST(RveBalance, ManyBusyGroupsAreRelievedTogetherAtTheCostOfOneMove) {
  // Groups 0..3 carry 3 + 3 = 6, groups 4..7 nothing: one point of each busy group to an idle
  // one gives 3 everywhere. The four moves run in parallel (one per group): over one update they
  // gain 6 - 3 = 3, which pays a move cost of 2.9 but not of 3. Costed per moved point
  // (4 × 2.9) no move would pay.
  const std::vector<double> cost{3, 3, 3, 3, 3, 3, 3, 3};
  const std::vector<int> owner{0, 0, 1, 1, 2, 2, 3, 3};
  const BalancePlan plan = plan_moves(cost, owner, 8, 0.0, 1, 2.9);
  EXPECT_EQ(plan.moves, 4u);
  EXPECT_EQ(plan.makespan_after, 3.0);
  EXPECT_EQ(makespan(cost, plan.owner, 8), 3.0);
  const std::vector<double> load = group_loads(cost, plan.owner, 8);
  EXPECT_EQ(*std::min_element(load.begin(), load.end()), 3.0);
  EXPECT_EQ(plan_moves(cost, owner, 8, 0.0, 1, 3.0).moves, 0u);
}

TEST(RveBalance, TwoMovesIntoOneGroupCostTwo) {
  // Groups 0 and 1 carry 3 each, group 2 nothing: one point of each to group 2 gives 2, 2, 2.
  // Group 2 receives both, so the moves take 2 × move_cost: the gain of 1 pays 0.49, not 0.5.
  const std::vector<double> cost{1, 1, 1, 1, 1, 1};
  const std::vector<int> owner{0, 0, 0, 1, 1, 1};
  EXPECT_EQ(plan_moves(cost, owner, 3, 0.0, 1, 0.49).moves, 2u);
  EXPECT_EQ(plan_moves(cost, owner, 3, 0.0, 1, 0.5).moves, 0u);
}

TEST(RveBalance, LongestProcessingTimeFirstKnownCase) {
  // The textbook case where LPT ends at 10 while 9 ({5, 4}, {3, 3, 3}) is optimal.
  const std::vector<double> cost{3, 5, 3, 4, 3};
  const std::vector<int> owner = lpt_owners(cost, 2);
  EXPECT_EQ(makespan(cost, owner, 2), 10.0);
  EXPECT_EQ(owner[1], 0);  // the costliest first, to the lowest group
  EXPECT_EQ(owner[3], 1);
}

TEST(RveBalance, StepTotals) {
  StepTotals t;
  t.add({3, 1}, {0, 1}, 2);  // work 4, busiest 3, bound max(3, 2) = 3
  t.add({1, 1}, {0, 0}, 2);  // work 2, busiest 2, bound max(1, 1) = 1
  EXPECT_EQ(t.work, 6.0);
  EXPECT_EQ(t.makespan, 5.0);
  EXPECT_EQ(t.bound, 4.0);
  EXPECT_DOUBLE_EQ(t.efficiency(2), 6.0 / 10.0);
  EXPECT_DOUBLE_EQ(t.bound_efficiency(2), 6.0 / 8.0);
  double saved[StepTotals::kValues];
  t.save(saved);
  StepTotals u;
  u.load(saved);
  EXPECT_EQ(u.makespan, t.makespan);
  EXPECT_EQ(StepTotals{}.efficiency(4), 1.0);
}
