#include "coupling/rve_balance.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
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
  s.persistence = node.in_range_or("persistence", 0.0, 1.0, s.persistence);
  // Above 0.95 the horizon would need more than 135 rows of loads per plan (peaks that last).
  if (s.persistence > 0.95 && s.persistence < 1.0)
    node.fail("persistence", "must be at most 0.95, or 1 (peaks that stay)");
  const std::string speed = node.get_or<std::string>("rank_speed", "equal");
  if (speed != "equal" && speed != "measured")
    node.fail("rank_speed", "must be \"equal\" or \"measured\", not \"" + speed + "\"");
  s.measured_speed = speed == "measured";
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

// The point of group `from` whose move evens the two loads best without making `to` the busier
// (cost × slow_to below `diff`), or npos. Equal speeds: the cost closest to half of `diff`.
std::size_t point_to_move(const std::vector<std::size_t>& members, const std::vector<double>& cost,
                          double diff, double slow_from, double slow_to) {
  std::size_t pick = std::string::npos;
  double pick_miss = 0.0;
  const double even = diff / (slow_from + slow_to);
  for (const std::size_t i : members) {
    if (cost[i] <= 0.0 || cost[i] * slow_to >= diff)
      continue;
    const double miss = std::abs(cost[i] - even);
    if (pick == std::string::npos || miss < pick_miss) {
      pick = i;
      pick_miss = miss;
    }
  }
  return pick;
}

// The largest of n values, kept as they change: a change costs log n, the maximum nothing.
class MaxTree {
 public:
  explicit MaxTree(const std::vector<double>& values) : n_(values.size()), node_(2 * n_, 0.0) {
    std::copy(values.begin(), values.end(), node_.begin() + static_cast<std::ptrdiff_t>(n_));
    for (std::size_t i = n_ - 1; i >= 1; --i)
      node_[i] = std::max(node_[2 * i], node_[2 * i + 1]);
  }
  void add(std::size_t index, double change) {
    std::size_t i = index + n_;
    node_[i] += change;
    for (i /= 2; i >= 1; i /= 2)
      node_[i] = std::max(node_[2 * i], node_[2 * i + 1]);
  }
  double max() const { return node_[1]; }

 private:
  std::size_t n_;
  std::vector<double> node_;  //!< node i holds the larger of 2i and 2i + 1; leaves from n_
};

// The groups' loads over the horizon: for ρ < 1 one row per update whose cost still differs
// from the floor by more than a thousandth of its excess, then the floor for the remaining
// updates; otherwise (or when no point is above its floor) the coming update's loads counted
// `horizon` times.
class HorizonLoads {
 public:
  HorizonLoads(const std::vector<double>& cost, const std::vector<double>& floor,
               double persistence, int horizon, const std::vector<int>& owner,
               const std::vector<double>& slow)
      : cost_(cost), slow_(slow) {
    bool decays = !floor.empty() && persistence < 1.0;
    if (decays) {
      floor_.resize(cost.size());
      bool peaks = false;
      for (std::size_t i = 0; i < cost.size(); ++i) {
        floor_[i] = std::min(floor[i], cost[i]);
        peaks = peaks || floor_[i] < cost[i];
      }
      decays = peaks;
    }
    int exact = 1;
    if (decays && persistence > 0.0) {
      const double rows = std::ceil(std::log(1e-3) / std::log(persistence));
      exact = rows >= static_cast<double>(horizon) ? horizon : static_cast<int>(rows);
    }
    exact = std::min(exact, horizon);
    double factor = 1.0;
    for (int k = 0; k < exact; ++k, factor *= persistence)
      share_.push_back(decays ? factor : 1.0);
    weight_.assign(share_.size(), 1.0);
    if (!decays) {
      weight_[0] = static_cast<double>(horizon);
    } else if (exact < horizon) {
      share_.push_back(0.0);  // the floor alone
      weight_.push_back(static_cast<double>(horizon - exact));
    }
    if (!decays)
      floor_.clear();
    for (std::size_t k = 0; k < share_.size(); ++k) {
      std::vector<double> load(slow.size(), 0.0);
      for (std::size_t i = 0; i < cost.size(); ++i)
        load[static_cast<std::size_t>(owner[i])] += point_cost(k, i);
      for (std::size_t g = 0; g < load.size(); ++g)
        load[g] *= slow[g];
      rows_.emplace_back(load);
      before_.push_back(rows_.back().max());
    }
  }
  void move(std::size_t point, std::size_t from, std::size_t to) {
    for (std::size_t k = 0; k < rows_.size(); ++k) {
      rows_[k].add(from, -point_cost(k, point) * slow_[from]);
      rows_[k].add(to, point_cost(k, point) * slow_[to]);
    }
  }
  //! Σ over the horizon of (makespan before - makespan now).
  double gain() const {
    double sum = 0.0;
    for (std::size_t k = 0; k < rows_.size(); ++k)
      sum += weight_[k] * (before_[k] - rows_[k].max());
    return sum;
  }

 private:
  double point_cost(std::size_t k, std::size_t i) const {
    if (floor_.empty() || share_[k] == 1.0)
      return cost_[i];
    return floor_[i] + share_[k] * (cost_[i] - floor_[i]);
  }
  const std::vector<double>& cost_;
  std::vector<double> floor_;  //!< min(floor, cost); empty when nothing decays
  const std::vector<double>& slow_;
  std::vector<double> share_, weight_, before_;
  std::vector<MaxTree> rows_;
};

}  // namespace

BalancePlan plan_moves(const std::vector<double>& cost, const std::vector<int>& owner, int groups,
                       double threshold, int horizon, double move_cost,
                       const std::vector<double>& slowness, const std::vector<double>& floor,
                       double persistence) {
  if (owner.size() != cost.size() || (!floor.empty() && floor.size() != cost.size()) ||
      (!slowness.empty() && slowness.size() != static_cast<std::size_t>(groups)))
    throw std::invalid_argument("plan_moves: the costs, owners, floors and speeds do not match");
  for (const double f : slowness) {
    if (!(f > 0.0) || !std::isfinite(f))
      throw std::invalid_argument("plan_moves: a group's slowness must be finite and positive");
  }
  BalancePlan plan;
  plan.owner = owner;
  const std::vector<double> slow =
      slowness.empty() ? std::vector<double>(static_cast<std::size_t>(groups), 1.0) : slowness;
  std::vector<double> load = group_loads(cost, owner, groups);
  const double total = std::accumulate(load.begin(), load.end(), 0.0);
  double capacity = 0.0;  // Σ 1/slowness: the groups' combined speed (`groups` when equal)
  for (std::size_t g = 0; g < load.size(); ++g) {
    load[g] *= slow[g];  // a group's load is its predicted time from here on
    capacity += 1.0 / slow[g];
  }
  plan.makespan_before = plan.makespan_after = load[busiest(load)];
  if (groups < 2 || total <= 0.0 || plan.makespan_before <= (1.0 + threshold) * total / capacity)
    return plan;
  // With equal speeds each move lowers Σ load² (c < diff), so the loop ends; with unequal
  // ones it need not, and the cap ends it.
  std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(groups));
  for (std::size_t i = 0; i < cost.size(); ++i)
    members[static_cast<std::size_t>(owner[i])].push_back(i);
  HorizonLoads future(cost, floor, persistence, horizon, owner, slow);
  std::vector<int> trial = owner;
  std::vector<int> touched(static_cast<std::size_t>(groups), 0);
  std::vector<std::pair<std::size_t, int>> sequence;  // (point, its new group) per move
  std::size_t best_prefix = 0;
  double best_value = 0.0;
  for (std::size_t step = 0; step < 2 * cost.size() + 2; ++step) {
    const std::size_t from = busiest(load), to = idlest(load);
    const std::size_t pick =
        point_to_move(members[from], cost, load[from] - load[to], slow[from], slow[to]);
    if (pick == std::string::npos)
      break;
    count_move(touched, owner[pick], trial[pick], -1);
    trial[pick] = static_cast<int>(to);
    count_move(touched, owner[pick], trial[pick], +1);
    auto& left = members[from];
    left.erase(std::find(left.begin(), left.end(), pick));
    auto& joined = members[to];
    joined.insert(std::lower_bound(joined.begin(), joined.end(), pick), pick);
    load[from] -= cost[pick] * slow[from];
    load[to] += cost[pick] * slow[to];
    future.move(pick, from, to);
    sequence.emplace_back(pick, trial[pick]);
    const double makespan = load[busiest(load)];
    const double value = future.gain() - move_cost * busiest_migration(touched);
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

void GroupSpeed::observe(const std::vector<double>& work, const std::vector<double>& seconds,
                         const std::vector<int>& owner) {
  const int groups = static_cast<int>(seconds_per_work_.size());
  const std::vector<double> w = group_loads(work, owner, groups);
  const std::vector<double> t = group_loads(seconds, owner, groups);
  // A fifth of each new measure: timer noise averages out over a few updates, and a core that
  // slows down (another job started on it) is followed within about ten.
  constexpr double kWeight = 0.2;
  for (std::size_t g = 0; g < w.size(); ++g) {
    if (!(w[g] > 0.0) || !(t[g] > 0.0))  // nothing run, or a timer that read nonsense
      continue;
    const double now = t[g] / w[g];
    double& s = seconds_per_work_[g];
    s = s > 0.0 ? (1.0 - kWeight) * s + kWeight * now : now;
  }
}

std::vector<double> GroupSpeed::slowness() const {
  double sum = 0.0;
  int measured = 0;
  for (const double s : seconds_per_work_) {
    if (s > 0.0) {
      sum += s;
      ++measured;
    }
  }
  std::vector<double> out(seconds_per_work_.size(), 1.0);
  if (measured == 0)
    return out;
  const double mean = sum / measured;
  for (std::size_t g = 0; g < out.size(); ++g) {
    if (seconds_per_work_[g] > 0.0)
      out[g] = seconds_per_work_[g] / mean;
  }
  return out;
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
