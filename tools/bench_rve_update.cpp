// Fixed cost of one RVE update next to its DEM stepping (a benchmark tool, never a test).
//
// usage: bench_rve_update CASE.json [--grains N] [--updates M | --steps S]
//                         [--substeps 1,20,100] [--setup-every 1,20] [--varying] [--repeats R]
//                         [--cpu-time] [--json FILE]
//
// Prepares the packing of CASE.json's "rve" node once (with N grains if given), then, R times and
// alternately for every sub-step count n, clones it and times M updates of a small simple shear
// with n DEM steps each: the deformation alone (Rve::deform), with what an MPM point does besides
// (Rve::observe_health: stress, grain measures and overlaps for the health check), and with the
// full Rve::observe instead (the engine's contact forces as well: what an MPM point read before).
// A straight line through seconds per update against n gives the fixed cost per update
// (intercept) and the cost per DEM step (slope). Prints a table (medians of R) and writes it as
// JSON. --cpu-time times the process's CPU time instead of the wall clock (on a loaded machine).
// --setup-every K1,K2,...: the RVE's `setup_every` (the engine's full set-up before one update
// in K, the others continuing its run), each timed in turn within every repeat: side by side.
// --varying: the shear's direction turns a little at every update, so that every update changes
// the grains' streaming velocities as an MPM point's do (the plain shear changes them once).
// --steps S: every n runs the same S DEM steps (S/n updates) along the same strain path (with
// --varying the direction turns by 0.005 rad per DEM step, 0.1 rad per 20), so every n steps
// the packing through the same states and the line is straight: its slope is a step's cost on
// that path and its intercept what an update costs besides. With --updates M the n differ in
// how far the packing is sheared (M n steps), a step's cost changes with it, and the intercept
// carries that difference as well.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <time.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/case_error.h"
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
  int steps = 0;  // > 0: the same DEM steps for every n (--steps)
  bool cpu_time = false;
  bool varying = false;
  std::vector<int> substeps = {1, 20, 100};
  std::vector<int> setup_every = {1};
};

std::vector<int> int_list(const std::string& text) {
  std::vector<int> values;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');)
    values.push_back(std::stoi(item));
  return values;
}

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
    else if (a == "--steps")
      o.steps = std::stoi(value());
    else if (a == "--repeats")
      o.repeats = std::stoi(value());
    else if (a == "--cpu-time")
      o.cpu_time = true;
    else if (a == "--varying")
      o.varying = true;
    else if (a == "--json")
      o.json_file = value();
    else if (a == "--substeps")
      o.substeps = int_list(value());
    else if (a == "--setup-every")
      o.setup_every = int_list(value());
    else if (o.case_file.empty() && a.rfind("--", 0) != 0)
      o.case_file = a;
    else
      throw std::invalid_argument("unknown argument '" + a + "'");
  }
  const bool setup_ok =
      !o.setup_every.empty() && *std::min_element(o.setup_every.begin(), o.setup_every.end()) >= 1;
  if (o.case_file.empty() || o.substeps.size() < 2 || o.updates < 1 || o.repeats < 1 || !setup_ok)
    throw std::invalid_argument(
        "usage: bench_rve_update CASE.json [--grains N] [--updates M | --steps S] "
        "[--substeps 1,20,100] [--setup-every 1,20] [--varying] [--repeats R] [--cpu-time] "
        "[--json FILE]");
  if (o.steps < 0)
    throw std::invalid_argument("--steps must be > 0");
  for (const int n : o.substeps)
    if (n < 1 || (o.steps > 0 && o.steps % n != 0))
      throw std::invalid_argument("every --substeps value must be >= 1 and divide --steps");
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

//! Seconds per update with n sub-steps on a fresh clone: o.updates updates, or o.steps / n along
//! one path (--steps). With --varying the shear's axes turn by 0.1 rad per update, or along one
//! path by 0.005 rad per DEM step.
double time_updates(const rve::RveSpec& spec, const std::string& packing, int n, Look look,
                    const Options& o) {
  const int updates = o.steps > 0 ? o.steps / n : o.updates;
  auto r = rve::Rve::from_restart(spec, packing, MPI_COMM_SELF, "bench");
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 1e-5 * n;  // the same shear rate per DEM step for every n
  const double start = now_seconds(o.cpu_time);
  for (int k = 0; k < updates; ++k) {
    if (o.varying) {
      // A pure shear whose axes turn at every update: a new velocity gradient each time.
      const double angle = o.steps > 0 ? 0.005 * k * n : 0.1 * k;
      const double rate = 1e-5 * n;
      dF = Mat3::Identity();
      dF(0, 0) += rate * std::cos(angle);
      dF(1, 1) -= rate * std::cos(angle);
      dF(0, 1) = dF(1, 0) = rate * std::sin(angle);
    }
    if (rve::starts_setup_period(spec, k))
      r->require_setup();
    r->deform(dF, n, rve::update_engine_run(spec));
    if (look == Look::health)
      r->check_blow_up(r->observe_health());
    else if (look == Look::full)
      r->check_blow_up(r->observe());
  }
  return (now_seconds(o.cpu_time) - start) / updates;
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

//! Prints the table of one `setup_every` and returns it as JSON.
nlohmann::json report(const rve::RveSpec& spec, const Options& o, int setup_every,
                      const std::vector<double>& x, const std::vector<double>& deform_only,
                      const std::vector<double>& with_observe,
                      const std::vector<double>& with_full) {
  const auto [fixed_deform, per_step] = line(x, deform_only);
  const auto [fixed_total, per_step_total] = line(x, with_observe);
  const auto [fixed_full, per_step_full] = line(x, with_full);
  const std::string runs = o.steps > 0 ? std::to_string(o.steps) + " DEM steps on one path"
                                       : std::to_string(o.updates) + " updates";
  std::printf("%ld grains, setup_every %d, %s x %d repeats (medians, %s%s)\n", spec.grains,
              setup_every, runs.c_str(), o.repeats, o.cpu_time ? "CPU time" : "wall clock",
              o.varying ? ", a new velocity gradient every update" : "");
  std::printf("%9s %10s %12s %12s %13s %13s\n", "substeps", "deform ms", "+ health ms", "+ full ms",
              "fixed share", "(full look)");
  nlohmann::json rows = nlohmann::json::array();
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
  return {{"grains", spec.grains},
          {"setup_every", setup_every},
          {"varying", o.varying},
          {"updates", o.steps > 0 ? nlohmann::json() : nlohmann::json(o.updates)},
          {"steps", o.steps},
          {"repeats", o.repeats},
          {"rows", rows},
          {"fixed_deform_seconds", fixed_deform},
          {"clock", o.cpu_time ? "cpu" : "wall"},
          {"fixed_observe_seconds", fixed_total - fixed_deform},
          {"fixed_full_observe_seconds", fixed_full - fixed_deform},
          {"seconds_per_dem_step", per_step},
          {"seconds_per_dem_step_with_observe", per_step_total}};
}

//! The case file's "rve" node; std::invalid_argument when the file cannot be read.
nlohmann::json read_rve_node(const std::string& case_file) {
  std::ifstream in(case_file);
  if (!in)
    throw std::invalid_argument("cannot read the case file '" + case_file + "'");
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json root = nlohmann::json::parse(text.str());
  if (!root.contains("rve"))
    throw std::invalid_argument(case_file + ": no \"rve\" node");
  return root.at("rve");
}

//! Prepares the packing, times every sub-step count and setup_every, prints and writes tables.
void run(const Options& o) {
  nlohmann::json rve_json = read_rve_node(o.case_file);
  if (o.grains > 0)
    rve_json["grains"] = o.grains;
  rve_json.erase("restart_file");
  const auto doc = mpm_lig::CaseDocument::parse(nlohmann::json{{"rve", rve_json}}.dump());
  const rve::RveSpec spec = rve::parse_rve_spec(doc.root().child("rve"));
  // The prepared packing's restart file, removed however the bench ends.
  struct TemporaryFile {
    std::string path;
    ~TemporaryFile() {
      std::error_code ignored;  // a destructor must not throw; nothing to remove is fine
      std::filesystem::remove(path, ignored);
    }
  } packing{std::filesystem::temp_directory_path() /
            ("bench_rve_update_" + std::to_string(getpid()) + ".restart")};
  {
    auto prepared = rve::Rve::generate(spec, MPI_COMM_SELF, "bench");
    rve::consolidate(*prepared);
    prepared->write_restart(packing.path);
  }
  struct Series {
    std::vector<double> deform_only, with_observe, with_full;
  };
  std::vector<Series> series(o.setup_every.size());
  for (const int n : o.substeps) {
    std::vector<std::vector<double>> a(series.size()), b(series.size()), c(series.size());
    for (int k = 0; k < o.repeats; ++k) {
      for (std::size_t m = 0; m < series.size(); ++m) {
        rve::RveSpec timed = spec;
        timed.setup_every = o.setup_every[m];
        a[m].push_back(time_updates(timed, packing.path, n, Look::none, o));
        b[m].push_back(time_updates(timed, packing.path, n, Look::health, o));
        c[m].push_back(time_updates(timed, packing.path, n, Look::full, o));
      }
    }
    for (std::size_t m = 0; m < series.size(); ++m) {
      series[m].deform_only.push_back(median(a[m]));
      series[m].with_observe.push_back(median(b[m]));
      series[m].with_full.push_back(median(c[m]));
    }
  }
  const std::vector<double> x(o.substeps.begin(), o.substeps.end());
  nlohmann::json tables = nlohmann::json::array();
  for (std::size_t m = 0; m < series.size(); ++m)
    tables.push_back(report(spec, o, o.setup_every[m], x, series[m].deform_only,
                            series[m].with_observe, series[m].with_full));
  if (!o.json_file.empty()) {
    nlohmann::json out_json = tables.front();
    if (tables.size() > 1)
      out_json = nlohmann::json{{"grains", spec.grains}, {"tables", tables}};
    std::ofstream out(o.json_file);
    out << out_json.dump(1) << "\n";
    if (!out)
      throw std::runtime_error("cannot write '" + o.json_file + "'");
  }
}

}  // namespace

int main(int argc, char** argv) {
  mpm_lig::MpiSession mpi(&argc, &argv);
  try {
    run(parse(argc, argv));
    return 0;
  } catch (const mpm_lig::CaseError& e) {
    std::fprintf(stderr, "bench_rve_update: %s\n", e.what());
  } catch (const nlohmann::json::exception& e) {
    std::fprintf(stderr, "bench_rve_update: the case file is not valid JSON: %s\n", e.what());
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "bench_rve_update: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_rve_update: %s\n", e.what());
    return 1;
  }
  return 2;
}
