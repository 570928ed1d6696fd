#pragma once

#include <filesystem>
#include <string>

#include <mpi.h>

#include "rve/consolidation.h"
#include "rve/rve.h"

namespace mpm_lig::test {

//! A fresh folder `dir` with `dir`/packing.restart: a packing of `spec` generated and
//! consolidated (the clone source the RVE tests share). Returns the restart file.
inline std::string consolidated_packing(const rve::RveSpec& spec, const std::string& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string packing = dir + "/packing.restart";
  auto prepared = rve::Rve::generate(spec, MPI_COMM_WORLD, "prepared");
  rve::consolidate(*prepared);
  prepared->write_restart(packing);
  return packing;
}

}  // namespace mpm_lig::test
