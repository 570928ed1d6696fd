#include "coupling/rve_balance.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace mpm_lig::coupling {

BalanceSpec parse_balance(const CaseNode& node) {
  BalanceSpec s;
  s.enabled = node.get_or<bool>("enabled", s.enabled);
  s.threshold = node.in_range_or("threshold", 0.0, 10.0, s.threshold);
  s.horizon = node.get_or<int>("horizon", s.horizon);
  if (s.horizon < 1 || s.horizon > 1'000'000)
    node.fail("horizon", "must be between 1 and 1000000");
  s.update_cost = node.in_range_or("update_cost", 0.0, 1e6, s.update_cost);
  s.move_cost = node.in_range_or("move_cost", 0.0, 1e9, s.move_cost);
  return s;
}

std::vector<double> group_loads(const std::vector<double>& cost, const std::vector<int>& owner,
                                int groups) {
  std::vector<double> load(static_cast<std::size_t>(groups), 0.0);
  for (std::size_t i = 0; i < cost.size(); ++i)
    load[static_cast<std::size_t>(owner[i])] += cost[i];
  return load;
}

namespace {

std::size_t busiest(const std::vector<double>& load) {
  return static_cast<std::size_t>(std::max_element(load.begin(), load.end()) - load.begin());
}

std::size_t idlest(const std::vector<double>& load) {
  return static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
}

// Moves run in parallel, each group writing what leaves it and reading what arrives: their
// time is that of the group with the most moves in or out.
double busiest_migration(const std::vector<int>& touched) {
  return touched.empty() ? 0.0
                         : static_cast<double>(*std::max_element(touched.begin(), touched.end()));
}

// A point away from its group `was` counts as a move for both `was` and `now`.
void count_move(std::vector<int>& touched, int was, int now, int sign) {
  if (was == now)
    return;
  touched[static_cast<std::size_t>(was)] += sign;
  touched[static_cast<std::size_t>(now)] += sign;
}

// The point of group `from` whose cost is closest to half of `diff` (below it), or npos.
std::size_t point_to_move(const std::vector<std::size_t>& members, const std::vector<double>& cost,
                          double diff) {
  std::size_t pick = std::string::npos;
  double pick_miss = 0.0;
  for (const std::size_t i : members) {
    if (cost[i] <= 0.0 || cost[i] >= diff)
      continue;
    const double miss = std::abs(cost[i] - 0.5 * diff);
    if (pick == std::string::npos || miss < pick_miss) {
      pick = i;
      pick_miss = miss;
    }
  }
  return pick;
}

}  // namespace

BalancePlan plan_moves(const std::vector<double>& cost, const std::vector<int>& owner, int groups,
                       double threshold, int horizon, double move_cost) {
  BalancePlan plan;
  plan.owner = owner;
  std::vector<double> load = group_loads(cost, owner, groups);
  const double total = std::accumulate(load.begin(), load.end(), 0.0);
  plan.makespan_before = plan.makespan_after = load[busiest(load)];
  if (groups < 2 || total <= 0.0 ||
      plan.makespan_before <= (1.0 + threshold) * total / static_cast<double>(groups))
    return plan;
  // Each move lowers Σ load² (c < diff), so the loop ends; the cap only bounds the work.
  std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(groups));
  for (std::size_t i = 0; i < cost.size(); ++i)
    members[static_cast<std::size_t>(owner[i])].push_back(i);
  std::vector<int> trial = owner;
  std::vector<int> touched(static_cast<std::size_t>(groups), 0);
  std::vector<std::pair<std::size_t, int>> sequence;  // (point, its new group) per move
  std::size_t best_prefix = 0;
  double best_value = 0.0;
  for (std::size_t step = 0; step < 2 * cost.size() + 2; ++step) {
    const std::size_t from = busiest(load), to = idlest(load);
    const std::size_t pick = point_to_move(members[from], cost, load[from] - load[to]);
    if (pick == std::string::npos)
      break;
    count_move(touched, owner[pick], trial[pick], -1);
    trial[pick] = static_cast<int>(to);
    count_move(touched, owner[pick], trial[pick], +1);
    auto& left = members[from];
    left.erase(std::find(left.begin(), left.end(), pick));
    auto& joined = members[to];
    joined.insert(std::lower_bound(joined.begin(), joined.end(), pick), pick);
    load[from] -= cost[pick];
    load[to] += cost[pick];
    sequence.emplace_back(pick, trial[pick]);
    const double makespan = load[busiest(load)];
    const double value = static_cast<double>(horizon) * (plan.makespan_before - makespan) -
                         move_cost * busiest_migration(touched);
    if (value > best_value) {
      best_value = value;
      best_prefix = sequence.size();
      plan.makespan_after = makespan;
    }
  }
  for (std::size_t k = 0; k < best_prefix; ++k)
    plan.owner[sequence[k].first] = sequence[k].second;
  plan.moves = 0;
  for (std::size_t i = 0; i < owner.size(); ++i)
    plan.moves += plan.owner[i] != owner[i] ? 1 : 0;
  return plan;
}

std::vector<int> lpt_owners(const std::vector<double>& cost, int groups) {
  std::vector<std::size_t> order(cost.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  std::vector<double> load(static_cast<std::size_t>(groups), 0.0);
  std::vector<int> owner(cost.size(), 0);
  for (const std::size_t i : order) {
    const std::size_t g = idlest(load);
    owner[i] = static_cast<int>(g);
    load[g] += cost[i];
  }
  return owner;
}

void StepTotals::add(const std::vector<double>& cost, const std::vector<int>& owner, int groups) {
  const std::vector<double> load = group_loads(cost, owner, groups);
  const double sum = std::accumulate(load.begin(), load.end(), 0.0);
  const double most = load[busiest(load)];
  const double costliest = cost.empty() ? 0.0 : *std::max_element(cost.begin(), cost.end());
  work += sum;
  makespan += most;
  bound += std::max(costliest, sum / static_cast<double>(groups));
}

double StepTotals::efficiency(int groups) const {
  return makespan > 0.0 ? work / (static_cast<double>(groups) * makespan) : 1.0;
}

double StepTotals::bound_efficiency(int groups) const {
  return bound > 0.0 ? work / (static_cast<double>(groups) * bound) : 1.0;
}

void StepTotals::save(double* v) const {
  v[0] = work;
  v[1] = makespan;
  v[2] = bound;
}

void StepTotals::load(const double* v) {
  work = v[0];
  makespan = v[1];
  bound = v[2];
}

}  // namespace mpm_lig::coupling
