#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "materials/statistics.h"

namespace mpm_lig::materials {
namespace {

Report report_of(double count, double largest, double smallest, double hidden_total) {
  Report r;
  Statistic n = statistic("group.count", count);
  n.integer = true;
  Statistic h = statistic("group.hidden", hidden_total);
  h.written = false;
  r.values = {n, statistic("group.largest", largest, Combine::max),
              statistic("smallest", smallest, Combine::min), h};
  r.derived.push_back({"group.ratio",
                       [](const Statistics& t) -> std::optional<double> {
                         return t.value("group.hidden") / t.value("group.count");
                       },
                       {},
                       {}});
  return r;
}

TEST(Statistics, ReportsCombineByKeyAndWriteAtTheirPaths) {
  Statistics s;
  s.add(report_of(0.0, 0.0, 0.0, 0.0));  // a family's zero values come first
  s.add(report_of(3.0, 2.5, 0.5, 6.0));
  s.add(report_of(5.0, 1.5, 0.25, 10.0));
  EXPECT_EQ(s.value("group.count"), 8.0);
  EXPECT_EQ(s.value("group.largest"), 2.5);
  // A min starts from the first report's value, here the zero one.
  EXPECT_EQ(s.value("smallest"), 0.0);
  nlohmann::json summary;
  s.write(summary);
  EXPECT_TRUE(summary["group"]["count"].is_number_unsigned());
  EXPECT_EQ(summary["group"]["count"].get<int>(), 8);
  EXPECT_EQ(summary["group"]["largest"].get<double>(), 2.5);
  EXPECT_EQ(summary["group"]["ratio"].get<double>(), 2.0);  // 16 / 8, of the combined totals
  EXPECT_FALSE(summary["group"].contains("hidden"));
  EXPECT_THROW(s.value("absent"), std::logic_error);
}

TEST(Statistics, MinTakesTheFirstReportsValue) {
  Statistics s;
  s.add({{statistic("scale", 0.5, Combine::min)}, {}});
  s.add({{statistic("scale", 0.25, Combine::min)}, {}});
  s.add({{statistic("scale", 1.0, Combine::min)}, {}});
  EXPECT_EQ(s.value("scale"), 0.25);
}

TEST(Statistics, WhenHoldsOnlyForAPositiveTotal) {
  Report r;
  Statistic steps = statistic("steps", 0.0);
  Statistic shown = statistic("section.value", 4.0);
  shown.when = "steps";
  r.values = {steps, shown};
  r.derived.push_back({"section.derived",
                       [](const Statistics&) -> std::optional<double> { return 1.0; },
                       "steps",
                       {}});
  r.derived.push_back(
      {"never", [](const Statistics&) -> std::optional<double> { return std::nullopt; }, {}, {}});
  Statistics none;
  none.add(r);
  nlohmann::json summary;
  none.write(summary);
  EXPECT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary["steps"].get<double>(), 0.0);

  r.values[0].value = 2.0;
  Statistics some;
  some.add(r);
  nlohmann::json written;
  some.write(written);
  EXPECT_EQ(written["section"]["value"].get<double>(), 4.0);
  EXPECT_EQ(written["section"]["derived"].get<double>(), 1.0);
  EXPECT_FALSE(written.contains("never"));
}

TEST(Statistics, GatheredValuesAreWrittenAsARankList) {
  Statistic t = statistic("per_rank", 1.5);
  t.ranks = Ranks::gathered;
  Statistics s;
  s.add({{t}, {}});
  s.add({{t}, {}});
  nlohmann::json before;
  s.write(before);
  EXPECT_FALSE(before.contains("per_rank"));  // nothing gathered yet
  s.gather(MPI_COMM_WORLD);
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  ASSERT_EQ(s.per_rank("per_rank").size(), static_cast<std::size_t>(ranks));
  EXPECT_EQ(s.per_rank("per_rank")[0], 3.0);
  nlohmann::json after;
  s.write(after);
  EXPECT_EQ(after["per_rank"][0].get<double>(), 3.0);
}

TEST(Statistics, TimeSplitPartsAndProgressItems) {
  Statistic steps = statistic("steps", 3e6);
  steps.progress = "DEM %.3g M/s";
  steps.progress_scale = 1e-6;
  Report r;
  r.values = {statistic("time_split.a", 1.0), steps, statistic("time_split.b", 2.0)};
  r.derived.push_back(
      {"eff", [](const Statistics&) -> std::optional<double> { return 0.5; }, {}, "eff %.2f"});
  Statistics now;
  now.add(r);
  EXPECT_EQ(now.values_under("time_split."), (std::vector<double>{1.0, 2.0}));
  Statistics before;
  EXPECT_EQ(now.progress(before, 2.0), (std::vector<std::string>{"DEM 1.5 M/s", "eff 0.50"}));
  EXPECT_EQ(now.progress(now, 2.0), (std::vector<std::string>{"DEM 0 M/s", "eff 0.50"}));
  r.values[1].value = 0.0;  // a rate is shown only once its total is positive
  Statistics idle;
  idle.add(r);
  EXPECT_EQ(idle.progress(before, 2.0), (std::vector<std::string>{"eff 0.50"}));
}

}  // namespace
}  // namespace mpm_lig::materials
