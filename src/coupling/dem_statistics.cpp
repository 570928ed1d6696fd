#include "coupling/dem_statistics.h"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mpm_lig::coupling {
namespace {

using materials::Combine;
using materials::Derived;
using materials::Ranks;
using materials::Report;
using materials::Statistic;
using materials::statistic;
using materials::Statistics;

constexpr const char* kParticleSteps = "dem_particle_steps";

//! A value written only while the run made particle-steps.
Statistic with_steps(std::string key, double value, Combine combine = Combine::sum) {
  Statistic s = statistic(std::move(key), value, combine);
  s.when = kParticleSteps;
  return s;
}

//! A total only the derived entries read.
Statistic hidden(std::string key, double value) {
  Statistic s = statistic(std::move(key), value);
  s.written = false;
  return s;
}

//! `part` / `whole` of two totals, `otherwise` when the whole is not positive.
std::optional<double> ratio(const Statistics& t, const std::string& part, const std::string& whole,
                            double otherwise) {
  const double w = t.value(whole);
  return w > 0.0 ? t.value(part) / w : otherwise;
}

//! Σ work / (groups × Σ_steps busiest group's work) of the stepping totals `work`, `makespan`
//! (1 without any).
Derived efficiency(std::string key, std::string work, std::string makespan) {
  return {std::move(key),
          [work, makespan](const Statistics& t) -> std::optional<double> {
            const double m = t.value(makespan);
            return m > 0.0 ? t.value(work) / (t.value("stepping.rank_groups") * m) : 1.0;
          },
          kParticleSteps,
          {}};
}

//! The mean group's waiting for the busiest one, step by step (from the owners' times).
double waiting(const Statistics& t) {
  return t.value("stepping.makespan_seconds") -
         t.value("stepping.seconds") / t.value("stepping.rank_groups");
}

}  // namespace

Report dem_statistics(const DemCost& cost) {
  Report r;
  Statistic count = statistic("rve_count", static_cast<double>(cost.simulations));
  count.integer = true;
  Statistic steps = statistic(kParticleSteps, cost.particle_steps);
  steps.progress = "DEM %.3g M particle-steps/s";
  steps.progress_scale = 1e-6;
  Statistic per_rank = with_steps("dem_seconds_per_rank", cost.compute_seconds);
  per_rank.ranks = Ranks::gathered;
  r.values = {count,
              steps,
              statistic("time_split.dem", cost.compute_seconds),
              statistic("time_split.communication", cost.communication_seconds),
              statistic("time_split.preparation", cost.preparation_seconds),
              per_rank};
  // Of whole-run times: blind to the waiting of each step, which "stepping" shows.
  r.derived.push_back({"load_imbalance",
                       [](const Statistics& t) -> std::optional<double> {
                         const std::vector<double>& times = t.per_rank("dem_seconds_per_rank");
                         if (times.empty())
                           return std::nullopt;
                         double sum = 0.0, most = 0.0;
                         for (const double time : times) {
                           sum += time;
                           most = std::max(most, time);
                         }
                         return sum > 0.0 ? most * static_cast<double>(times.size()) / sum : 1.0;
                       },
                       kParticleSteps,
                       {}});
  return r;
}

void add_work_shares(Report& report, double at_max, double low_stress, double quiet) {
  const struct {
    const char* name;
    double value;
  } shares[] = {{"at_substeps_max", at_max},
                {"mean_stress_below_10_percent_of_preparation", low_stress},
                {"strain_per_step_below_1e-5", quiet}};
  for (const auto& share : shares) {
    const std::string steps = std::string("dem_work.") + share.name;
    report.values.push_back(hidden(steps, share.value));
    report.derived.push_back({std::string("dem_work_shares.") + share.name,
                              [steps](const Statistics& t) -> std::optional<double> {
                                return t.value(steps) / t.value(kParticleSteps);
                              },
                              kParticleSteps,
                              {}});
  }
}

void add_stepping(Report& report, const SteppingCounters& s) {
  report.values.push_back(with_steps("stepping.rank_groups", s.groups, Combine::max));
  for (const auto& [key, value] :
       {std::pair<const char*, double>{"stepping.work_predicted", s.predicted.work},
        {"stepping.makespan_predicted", s.predicted.makespan},
        {"stepping.work", s.measured.work},
        {"stepping.makespan", s.measured.makespan},
        {"stepping.bound", s.measured.bound},
        {"stepping.seconds", s.seconds.work},
        {"stepping.makespan_seconds", s.seconds.makespan}})
    report.values.push_back(hidden(key, value));
  report.values.push_back(with_steps("stepping.migrations", s.migrations));
  report.values.push_back(with_steps("stepping.rebalances", s.rebalances));
  report.values.push_back(with_steps("stepping.migration_seconds", s.migration_seconds));

  Derived measured = efficiency("stepping.efficiency", "stepping.work", "stepping.makespan");
  measured.progress = "stepping efficiency %.3f";
  report.derived.push_back(measured);
  report.derived.push_back(efficiency("stepping.efficiency_predicted", "stepping.work_predicted",
                                      "stepping.makespan_predicted"));
  report.derived.push_back(
      efficiency("stepping.efficiency_seconds", "stepping.seconds", "stepping.makespan_seconds"));
  report.derived.push_back(
      efficiency("stepping.efficiency_bound", "stepping.work", "stepping.bound"));
  report.derived.push_back({"stepping.waiting_seconds",
                            [](const Statistics& t) -> std::optional<double> { return waiting(t); },
                            kParticleSteps,
                            {}});
  report.derived.push_back({"stepping.waiting_share",
                            [](const Statistics& t) -> std::optional<double> {
                              const double wall = t.wall_seconds();
                              return wall > 0.0 ? waiting(t) / wall : 0.0;
                            },
                            kParticleSteps,
                            {}});
}

void add_quiet_points(Report& report, const QuietStats& q) {
  report.values.push_back(statistic("quiet_points.predicted_updates", q.predictions));
  report.values.push_back(statistic("quiet_points.dem_updates", q.dem_updates));
  report.values.push_back(statistic("quiet_points.checks", q.checks));
  report.values.push_back(hidden("quiet_points.error_sum", q.error_sum));
  report.values.push_back(statistic("quiet_points.max_error", q.max_error, Combine::max));
  report.values.push_back(statistic("quiet_points.checks_above_max_error", q.exceeded));
  report.derived.push_back({"quiet_points.predicted_share",
                            [](const Statistics& t) -> std::optional<double> {
                              const double p = t.value("quiet_points.predicted_updates");
                              const double all = p + t.value("quiet_points.dem_updates");
                              return all > 0.0 ? p / all : 0.0;
                            },
                            {},
                            {}});
  report.derived.push_back({"quiet_points.mean_error",
                            [](const Statistics& t) {
                              return ratio(t, "quiet_points.error_sum", "quiet_points.checks", 0.0);
                            },
                            {},
                            {}});
}

void add_steady_flow(Report& report, const SteadyFlowStats& f) {
  report.values.push_back(statistic("steady_flow.predicted_updates", f.predictions));
  report.values.push_back(statistic("steady_flow.flows_begun", f.entries));
  report.values.push_back(statistic("steady_flow.checks", f.checks));
  report.values.push_back(hidden("steady_flow.error_sum", f.error_sum));
  report.values.push_back(statistic("steady_flow.max_error", f.max_error, Combine::max));
  report.values.push_back(statistic("steady_flow.checks_above_max_error", f.exceeded));
  report.values.push_back(statistic("steady_flow.ended_by_drift", f.drifts));
  report.values.push_back(statistic("steady_flow.ended_by_turn", f.turns));
  report.values.push_back(statistic("steady_flow.ended_by_volume_change", f.volume_exits));
  report.values.push_back(statistic("steady_flow.skipped_shear_strain", f.skipped_shear));
  report.derived.push_back({"steady_flow.mean_error",
                            [](const Statistics& t) {
                              return ratio(t, "steady_flow.error_sum", "steady_flow.checks", 0.0);
                            },
                            {},
                            {}});
}

void add_continuum_start(Report& report, const QuietStats& q, double points) {
  report.values.push_back(statistic("start_as_continuum.continuum_updates", q.continuum_updates));
  report.values.push_back(statistic("start_as_continuum.switched_points", q.switches));
  report.values.push_back(hidden("start_as_continuum.jump_sum", q.jump_sum));
  report.values.push_back(statistic("start_as_continuum.max_jump", q.max_jump, Combine::max));
  report.values.push_back(statistic("start_as_continuum.jumps_above_max_jump", q.jumps_exceeded));
  report.values.push_back(
      statistic("start_as_continuum.threshold_scale", q.threshold_scale, Combine::min));
  report.values.push_back(hidden("start_as_continuum.points", points));
  report.derived.push_back({"start_as_continuum.continuum_points",
                            [](const Statistics& t) -> std::optional<double> {
                              return t.value("start_as_continuum.points") -
                                     t.value("start_as_continuum.switched_points");
                            },
                            {},
                            {}});
  report.derived.push_back({"start_as_continuum.mean_jump",
                            [](const Statistics& t) {
                              return ratio(t, "start_as_continuum.jump_sum",
                                           "start_as_continuum.switched_points", 0.0);
                            },
                            {},
                            {}});
}

}  // namespace mpm_lig::coupling
