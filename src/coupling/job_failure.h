#pragma once

#include <cstddef>
#include <exception>
#include <string>

#include "core/mpi_session.h"
#include "core/stop_signal.h"

namespace mpm_lig::coupling {

//! How a dem_rve material names one of its points in a message: its case path, the point and
//! this MPI rank.
struct PointLabel {
  std::string path;  //!< the material's JSON path ("materials[0]")
  int rank = 0;      //!< this rank in the run
  std::string operator()(std::size_t point) const {
    return path + " material point " + std::to_string(point) + " (MPI rank " +
           std::to_string(rank) + ")";
  }
};

//! Run `work` on one RVE's files; a failure ends the whole job at once with `what` and the
//! reason: the other ranks are about to wait for this one in a collective call.
template <class Work>
auto or_end_job(const std::string& what, Work&& work) {
  try {
    return work();
  } catch (const StopRequested&) {
    throw;  // agreed on by the RVE's ranks: the caller stops with the others
  } catch (const std::exception& e) {
    abort_job(what + ": " + e.what(), 1);
  }
}

}  // namespace mpm_lig::coupling
