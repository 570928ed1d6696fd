// Fixed cost of one RVE update next to its DEM stepping (a benchmark tool, never a test).
//
// usage: bench_rve_update CASE.json [--grains N] [--updates M] [--substeps 1,20,100]
//                         [--repeats R] [--cpu-time] [--json FILE]
//
// Prepares the packing of CASE.json's "rve" node once (with N grains if given), then, R times and
// alternately for every sub-step count n, clones it and times M updates of a small simple shear
// with n DEM steps each: the deformation alone (Rve::deform), with what an MPM point does besides
// (Rve::observe_health: stress, grain measures and overlaps for the health check), and with the
// full Rve::observe instead (the engine's contact forces as well: what an MPM point read before).
// A straight line through seconds per update against n gives the fixed cost per update
// (intercept) and the cost per DEM step (slope). Prints a table (medians of R) and writes it as
// JSON. --cpu-time times the process's CPU time instead of the wall clock (on a loaded machine).
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <time.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/case_node.h"
#include "core/mpi_session.h"
#include "rve/consolidation.h"
#include "rve/rve.h"
#include "rve/spec.h"

namespace {

using mpm_lig::Mat3;
namespace rve = mpm_lig::rve;

struct Options {
  std::string case_file, json_file;
  long grains = 0;
  int updates = 200, repeats = 3;
  bool cpu_time = false;
  std::vector<int> substeps = {1, 20, 100};
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
        throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--grains")
      o.grains = std::stol(value());
    else if (a == "--updates")
      o.updates = std::stoi(value());
    else if (a == "--repeats")
      o.repeats = std::stoi(value());
    else if (a == "--cpu-time")
      o.cpu_time = true;
    else if (a == "--json")
      o.json_file = value();
    else if (a == "--substeps") {
      o.substeps.clear();
      std::stringstream list(value());
      for (std::string item; std::getline(list, item, ',');)
        o.substeps.push_back(std::stoi(item));
    } else if (o.case_file.empty() && a.rfind("--", 0) != 0)
      o.case_file = a;
    else
      throw std::invalid_argument("unknown argument '" + a + "'");
  }
  if (o.case_file.empty() || o.substeps.size() < 2 || o.updates < 1 || o.repeats < 1)
    throw std::invalid_argument(
        "usage: bench_rve_update CASE.json [--grains N] [--updates M] "
        "[--substeps 1,20,100] [--repeats R] [--cpu-time] [--json FILE]");
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

//! Wall-clock or process CPU seconds.
double now_seconds(bool cpu_time) {
  if (!cpu_time)
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

enum class Look { none, health, full };

//! Seconds per update of `updates` updates with n sub-steps on a fresh clone.
double time_updates(const rve::RveSpec& spec, const std::string& packing, int n, int updates,
                    Look look, bool cpu_time) {
  auto r = rve::Rve::from_restart(spec, packing, MPI_COMM_SELF, "bench");
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 1e-5 * n;  // the same shear rate per DEM step for every n
  const double start = now_seconds(cpu_time);
  for (int k = 0; k < updates; ++k) {
    r->deform(dF, n);
    if (look == Look::health)
      r->check_blow_up(r->observe_health());
    else if (look == Look::full)
      r->check_blow_up(r->observe());
  }
  return (now_seconds(cpu_time) - start) / updates;
}

//! Least-squares line y = a + b x.
std::pair<double, double> line(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {(sy - b * sx) / n, b};
}

}  // namespace

int main(int argc, char** argv) {
  mpm_lig::MpiSession mpi(&argc, &argv);
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_rve_update: %s\n", e.what());
    return 2;
  }
  std::ifstream in(o.case_file);
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json rve_json = nlohmann::json::parse(text.str()).at("rve");
  if (o.grains > 0)
    rve_json["grains"] = o.grains;
  rve_json.erase("restart_file");
  const auto doc = mpm_lig::CaseDocument::parse(nlohmann::json{{"rve", rve_json}}.dump());
  const rve::RveSpec spec = rve::parse_rve_spec(doc.root().child("rve"));
  const std::string packing = std::filesystem::temp_directory_path() /
                              ("bench_rve_update_" + std::to_string(getpid()) + ".restart");
  {
    auto prepared = rve::Rve::generate(spec, MPI_COMM_SELF, "bench");
    rve::consolidate(*prepared);
    prepared->write_restart(packing);
  }
  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> x, deform_only, with_observe, with_full;
  for (const int n : o.substeps) {
    std::vector<double> a, b, c;
    for (int k = 0; k < o.repeats; ++k) {
      a.push_back(time_updates(spec, packing, n, o.updates, Look::none, o.cpu_time));
      b.push_back(time_updates(spec, packing, n, o.updates, Look::health, o.cpu_time));
      c.push_back(time_updates(spec, packing, n, o.updates, Look::full, o.cpu_time));
    }
    x.push_back(n);
    deform_only.push_back(median(a));
    with_observe.push_back(median(b));
    with_full.push_back(median(c));
  }
  std::filesystem::remove(packing);
  const auto [fixed_deform, per_step] = line(x, deform_only);
  const auto [fixed_total, per_step_total] = line(x, with_observe);
  const auto [fixed_full, per_step_full] = line(x, with_full);
  std::printf("%ld grains, %d updates x %d repeats (medians, %s)\n", spec.grains, o.updates,
              o.repeats, o.cpu_time ? "CPU time" : "wall clock");
  std::printf("%9s %10s %12s %12s %13s %13s\n", "substeps", "deform ms", "+ health ms", "+ full ms",
              "fixed share", "(full look)");
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double share = fixed_total / with_observe[i], share_full = fixed_full / with_full[i];
    std::printf("%9.0f %10.3f %12.3f %12.3f %12.1f%% %12.1f%%\n", x[i], 1e3 * deform_only[i],
                1e3 * with_observe[i], 1e3 * with_full[i], 100 * share, 100 * share_full);
    rows.push_back({{"substeps", x[i]},
                    {"deform_seconds", deform_only[i]},
                    {"update_seconds", with_observe[i]},
                    {"full_observe_update_seconds", with_full[i]},
                    {"fixed_share", share},
                    {"fixed_share_full_observe", share_full}});
  }
  std::printf(
      "fixed cost per update: deform %.3f ms, observe_health %.3f ms (observe %.3f ms); "
      "per DEM step %.4f ms (%.3g particle-steps/s)\n",
      1e3 * fixed_deform, 1e3 * (fixed_total - fixed_deform), 1e3 * (fixed_full - fixed_deform),
      1e3 * per_step, spec.grains / per_step);
  if (!o.json_file.empty()) {
    std::ofstream out(o.json_file);
    out << nlohmann::json{{"grains", spec.grains},
                          {"updates", o.updates},
                          {"repeats", o.repeats},
                          {"rows", rows},
                          {"fixed_deform_seconds", fixed_deform},
                          {"clock", o.cpu_time ? "cpu" : "wall"},
                          {"fixed_observe_seconds", fixed_total - fixed_deform},
                          {"fixed_full_observe_seconds", fixed_full - fixed_deform},
                          {"seconds_per_dem_step", per_step},
                          {"seconds_per_dem_step_with_observe", per_step_total}}
               .dump(1)
        << "\n";
  }
  return 0;
}
