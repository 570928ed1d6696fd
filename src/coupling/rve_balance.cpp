#include "coupling/rve_balance.h"

#include <algorithm>
#include <numeric>

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

std::size_t moved(const std::vector<int>& a, const std::vector<int>& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    n += a[i] != b[i] ? 1 : 0;
  return n;
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
  std::vector<int> trial = owner;
  double best_value = 0.0;
  for (std::size_t step = 0; step < 2 * cost.size() + 2; ++step) {
    const std::size_t from = busiest(load), to = idlest(load);
    const double diff = load[from] - load[to];
    std::size_t pick = cost.size();
    double pick_miss = 0.0;
    for (std::size_t i = 0; i < cost.size(); ++i) {
      if (static_cast<std::size_t>(trial[i]) != from || cost[i] <= 0.0 || cost[i] >= diff)
        continue;
      const double miss = std::abs(cost[i] - 0.5 * diff);
      if (pick == cost.size() || miss < pick_miss) {
        pick = i;
        pick_miss = miss;
      }
    }
    if (pick == cost.size())
      break;
    trial[pick] = static_cast<int>(to);
    load[from] -= cost[pick];
    load[to] += cost[pick];
    const double makespan = load[busiest(load)];
    const std::size_t moves = moved(owner, trial);
    const double value = static_cast<double>(horizon) * (plan.makespan_before - makespan) -
                         move_cost * static_cast<double>(moves);
    if (value > best_value) {
      best_value = value;
      plan.owner = trial;
      plan.moves = moves;
      plan.makespan_after = makespan;
    }
  }
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
