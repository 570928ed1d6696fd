// The exchange at the end of every MPM step of a dem_rve material: RveLayout::gather of
// 11 doubles per point (stress, DEM steps, seconds) from every rank group to every rank.
//
// usage: mpirun -np R bench_allgather [--points 64,1024,7776] [--repeats N] [--json FILE]
// Prints a table (ranks, points, microseconds per gather: median and minimum over the
// repeats, each the mean of a batch) and writes JSON for tools/scaling_model.py --gather.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <mpi.h>
#include <nlohmann/json.hpp>

#include "core/mpi_session.h"
#include "coupling/rve_layout.h"

int main(int argc, char** argv) {
  mpm_lig::MpiSession mpi(&argc, &argv);
  std::vector<std::size_t> point_counts{64, 1024, 7776};
  int repeats = 7;
  std::string json_file;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--points" && i + 1 < argc) {
      point_counts.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');)
        point_counts.push_back(std::stoul(item));
    } else if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--json" && i + 1 < argc) {
      json_file = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: bench_allgather [--points a,b,...] [--repeats N] [--json FILE]\n");
      return 2;
    }
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  constexpr int kWidth = 11;
  nlohmann::json rows = nlohmann::json::array();
  if (rank == 0)
    std::printf("%6s %8s %14s %14s\n", "ranks", "points", "median [us]", "min [us]");
  for (const std::size_t points : point_counts) {
    mpm_lig::coupling::RveLayout layout(MPI_COMM_WORLD, 1, points);
    const std::vector<double> owned(layout.owned().size() * kWidth, 1.0);
    const int batch = std::max<int>(5, static_cast<int>(200000 / (points + 100)));
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
      MPI_Barrier(MPI_COMM_WORLD);
      const double start = MPI_Wtime();
      for (int b = 0; b < batch; ++b)
        layout.gather(owned, kWidth);
      double t = (MPI_Wtime() - start) / batch;
      MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
      times.push_back(t);
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2], best = times.front();
    if (rank == 0)
      std::printf("%6d %8zu %14.2f %14.2f\n", ranks, points, median * 1e6, best * 1e6);
    rows.push_back({{"ranks", ranks},
                    {"points", points},
                    {"median_seconds", median},
                    {"min_seconds", best},
                    {"repeats", repeats},
                    {"batch", batch}});
  }
  if (rank == 0 && !json_file.empty()) {
    std::ofstream out(json_file);
    out << nlohmann::json{{"bench", "allgather"}, {"width", kWidth}, {"rows", rows}}.dump(1)
        << '\n';
    if (!out) {
      std::fprintf(stderr, "bench_allgather: cannot write '%s'\n", json_file.c_str());
      return 1;
    }
  }
  return 0;
}
