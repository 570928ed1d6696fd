// Times DEM runs through the library API (see bench_engine.py, which drives it).
// usage: bench_engine ENGINE SETUP_SCRIPT STEPS CHUNK
//   Creates one instance, runs SETUP_SCRIPT, then times STEPS steps issued as `run CHUNK`
//   commands (CHUNK = STEPS: one call). Prints one JSON object on stdout.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/mpi_session.h"
#include "dem/engine.h"

int main(int argc, char** argv) {
  mpm_lig::MpiSession mpi(&argc, &argv);
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s ENGINE SETUP_SCRIPT STEPS CHUNK\n", argv[0]);
    return 2;
  }
  const std::string engine_name = argv[1];
  std::ifstream file(argv[2]);
  std::stringstream setup;
  setup << file.rdbuf();
  const long steps = std::stol(argv[3]), chunk = std::stol(argv[4]);

  auto engine = mpm_lig::dem::create_engine(engine_name, MPI_COMM_SELF, {"benchmark", ""});
  engine->commands(setup.str());
  const auto start = std::chrono::steady_clock::now();
  for (long done = 0; done < steps; done += chunk)
    engine->command("run " + std::to_string(chunk) + " pre yes post no");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json result = {{"engine", engine_name}, {"atoms", engine->atom_count()},
                           {"steps", steps},        {"chunk", chunk},
                           {"seconds", seconds},    {"pressure", engine->compute_vector("p", 6)}};
  std::cout << result.dump() << std::endl;
  return 0;
}
