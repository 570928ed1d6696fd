// MPM throughput: material-point updates per second (points x steps / wall time of the step
// loop), one core, for a gravity-loaded elastic block with rollers and local damping.
//
// usage: bench_mpm [--steps N] [--json FILE]
// Prints a table (dimension, shape functions, scheme, points, updates/s) and writes JSON.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/case_node.h"
#include "materials/material.h"
#include "mpm/case_spec.h"
#include "mpm/driver.h"
#include "mpm/solver.h"

namespace {

using mpm_lig::mpm::MpmProblem;

struct Variant {
  int dimension;
  int cells;  // per axis
  std::string shape;
  std::string scheme;
};

nlohmann::json make_case(const Variant& v) {
  const double size = 1.0, height = 0.8;
  nlohmann::json j;
  j["dimension"] = v.dimension;
  j["analysis"] = {
      {"type", "mpm"},   {"shape_function", v.shape},   {"scheme", v.scheme},   {"flip", 0.98},
      {"damping", 0.05}, {"time_step", {{"cfl", 0.5}}}, {"end", {{"steps", 1}}}};
  std::vector<double> origin(v.dimension, 0.0), mesh(v.dimension, size), body(v.dimension, size);
  body.back() = height;
  j["mesh"] = {
      {"origin", origin}, {"size", mesh}, {"cells", std::vector<int>(v.dimension, v.cells)}};
  j["materials"] = {{{"id", 0},
                     {"type", "linear_elastic"},
                     {"density", 2000.0},
                     {"youngs_modulus", 1e7},
                     {"poisson_ratio", 0.3}}};
  j["bodies"] = {
      {{"material", 0}, {"box", {{"min", origin}, {"max", body}}}, {"points_per_cell", 2}}};
  nlohmann::json bcs = {{{"type", "fixed"}, {"nodes", {{"face", v.dimension == 2 ? "y-" : "z-"}}}}};
  const char* axes[] = {"x", "y"};
  for (int d = 0; d < v.dimension - 1; ++d) {
    for (const char* side : {"-", "+"}) {
      bcs.push_back({{"type", "roller"},
                     {"nodes", {{"face", std::string(axes[d]) + side}}},
                     {"direction", axes[d]}});
    }
  }
  j["boundary_conditions"] = bcs;
  std::vector<double> g(v.dimension, 0.0);
  g.back() = -9.81;
  j["gravity"] = g;
  return j;
}

template <int D>
double updates_per_second(MpmProblem& c, long steps, std::size_t& points) {
  mpm_lig::mpm::prepare_materials(c, MPI_COMM_SELF, "bench_mpm_packings");  // continuum: no files
  mpm_lig::mpm::Solver<D> solver(c.spec, std::move(c.materials));
  points = solver.particles().size();
  solver.step();  // warm-up: first touch of the work arrays
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k)
    solver.step();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return static_cast<double>(points) * steps / wall;
}

}  // namespace

int main(int argc, char** argv) {
  long steps = 200;
  std::string json_file = "bench_mpm.json";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) {
      char* end = nullptr;
      steps = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || steps < 1) {
        std::fprintf(stderr, "bench_mpm: --steps '%s': expected a whole number >= 1\n", argv[i]);
        return 2;
      }
    } else if (!std::strcmp(argv[i], "--json") && i + 1 < argc) {
      json_file = argv[++i];
    } else {
      std::fprintf(stderr, "usage: bench_mpm [--steps N] [--json FILE]\n");
      return 2;
    }
  }
  mpm_lig::materials::MaterialRegistry registry;
  mpm_lig::materials::register_materials(registry);
  const std::vector<Variant> variants = {{2, 50, "linear", "musl"}, {2, 100, "linear", "musl"},
                                         {2, 100, "linear", "usl"}, {2, 100, "gimp", "musl"},
                                         {3, 16, "linear", "musl"}, {3, 16, "gimp", "musl"}};
  nlohmann::json results = nlohmann::json::array();
  std::printf("%-4s %-7s %-5s %9s %14s\n", "dim", "shape", "scheme", "points", "updates/s");
  for (const Variant& v : variants) {
    const auto document = mpm_lig::CaseDocument::parse(make_case(v).dump());
    MpmProblem c = mpm_lig::mpm::read_case(document.root(), registry);
    std::size_t points = 0;
    const double rate = v.dimension == 2 ? updates_per_second<2>(c, steps, points)
                                         : updates_per_second<3>(c, steps, points);
    std::printf("%-4d %-7s %-5s %9zu %14.3e\n", v.dimension, v.shape.c_str(), v.scheme.c_str(),
                points, rate);
    results.push_back({{"dimension", v.dimension},
                       {"shape_function", v.shape},
                       {"scheme", v.scheme},
                       {"material_points", points},
                       {"steps", steps},
                       {"updates_per_second", rate}});
  }
  std::ofstream(json_file) << nlohmann::json{{"benchmark", "mpm"}, {"results", results}}.dump(2)
                           << '\n';
  std::printf("written %s\n", json_file.c_str());
  return 0;
}
