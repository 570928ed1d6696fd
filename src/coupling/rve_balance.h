#pragma once

#include <cstddef>
#include <vector>

#include "core/case_node.h"

namespace mpm_lig::coupling {

//! Case node "balance" of a dem_rve material: RVEs moved between rank groups by the predicted
//! cost of their coming update (docs/DESIGN.md §7). Costs are in DEM steps of one RVE.
struct BalanceSpec {
  bool enabled = true;
  double threshold = 0.02;   //!< predicted max/mean group load - 1 above which moves are sought
  int horizon = 10;          //!< updates over which a move's predicted gain is counted
  double update_cost = 5.0;  //!< fixed cost of one update besides its DEM steps
  double move_cost = 60.0;   //!< cost of moving one RVE to another group
  //! Share of a point's cost above its sub-step floor expected to remain one update later
  //! (the floor itself stays): 1 counts the coming update's gain `horizon` times.
  double persistence = 0.6;
  //! "measured": loads weighted by each group's measured seconds per unit of work, so that
  //! unequal cores get unequal shares; decisions then depend on timings (results do not).
  bool measured_speed = false;
};

BalanceSpec parse_balance(const CaseNode& node);

//! Sum of `cost` over the points each group owns (`owner[i]` the group of point i).
std::vector<double> group_loads(const std::vector<double>& cost, const std::vector<int>& owner,
                                int groups);

//! Each rank group's seconds per unit of work, smoothed over updates (`"rank_speed":
//! "measured"`): the balancer then evens out predicted seconds instead of work.
class GroupSpeed {
 public:
  explicit GroupSpeed(int groups) : seconds_per_work_(static_cast<std::size_t>(groups), 0.0) {}
  //! One update's measured work and seconds of every point, `owner[i]` the group that ran i.
  void observe(const std::vector<double>& work, const std::vector<double>& seconds,
               const std::vector<int>& owner);
  //! Each group's seconds per work over the groups' mean (1 for a group not measured yet).
  std::vector<double> slowness() const;

 private:
  std::vector<double> seconds_per_work_;  //!< 0 until the group has run work
};

//! New owners for the points, from their predicted costs of the coming update.
struct BalancePlan {
  std::vector<int> owner;        //!< every point's group after the moves
  std::size_t moves = 0;         //!< points whose group changes
  double makespan_before = 0.0;  //!< the busiest group's load with the old owners
  double makespan_after = 0.0;   //!< and with the new ones
};

//! Moves of single points from the busiest group to the least busy one, each the point whose
//! cost is closest to half their difference (fewest moves from the busiest groups), kept up to
//! the prefix whose gain `horizon` × (makespan reduction) exceeds the time of its moves by the
//! most. The moves run in parallel: their time is `move_cost` × the most moves into or out of
//! one group, so relieving many busy groups at once costs about as much as relieving one. No moves
//! when the imbalance max/mean - 1 is at most `threshold`, or when no prefix gains. Deterministic
//! (ties to the lowest index): every rank plans the same. With `slowness` (one factor per group,
//! GroupSpeed) a group's load is its cost × its factor; empty means all groups equal.
//! With `floor` (each point's cost at its fewest sub-steps, capped at its cost) and `persistence`
//! ρ < 1, update k of the horizon (k = 0 the coming one) costs floor + ρ^k (cost - floor) and a
//! prefix's gain is the sum over the horizon of the makespan reductions: a move that evens the
//! coming update by piling points on one group loses once the peaks have passed.
BalancePlan plan_moves(const std::vector<double>& cost, const std::vector<int>& owner, int groups,
                       double threshold, int horizon, double move_cost,
                       const std::vector<double>& slowness = {},
                       const std::vector<double>& floor = {}, double persistence = 1.0);

//! Longest processing time first: points by decreasing cost, each to the least loaded group
//! (the reference the scaling model compares with; ignores where the points are now).
std::vector<int> lpt_owners(const std::vector<double>& cost, int groups);

//! Per-step loads of the rank groups, summed over the run: the stepping efficiency
//! Σ work / (groups × Σ_steps max_group work) and its bound, the costliest point alone.
struct StepTotals {
  double work = 0.0;      //!< Σ over steps and points
  double makespan = 0.0;  //!< Σ over steps of the busiest group's load
  double bound = 0.0;     //!< Σ over steps of max(costliest point, mean group load)
  void add(const std::vector<double>& cost, const std::vector<int>& owner, int groups);
  double efficiency(int groups) const;
  double bound_efficiency(int groups) const;
  static constexpr int kValues = 3;
  void save(double* v) const;
  void load(const double* v);
};

}  // namespace mpm_lig::coupling
