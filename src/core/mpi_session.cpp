#include "core/mpi_session.h"

#include <cstdio>
#include <cstdlib>

#include <mpi.h>

namespace mpm_lig {
namespace {

bool g_orderly_shutdown = false;
std::function<std::string()>& fatal_reporter() {
  static std::function<std::string()> reporter;
  return reporter;
}

}  // namespace

MpiSession::MpiSession(int* argc, char*** argv) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised)
    MPI_Init(argc, argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  g_orderly_shutdown = true;
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized)
    MPI_Finalize();
}

void set_fatal_reporter(std::function<std::string()> reporter) {
  fatal_reporter() = std::move(reporter);
}

void abort_job(const std::string& message, int exit_code) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::fprintf(stderr, "mpm_lig: rank %d: %s\n", rank, message.c_str());
  std::fflush(stderr);
  PMPI_Abort(MPI_COMM_WORLD, exit_code);  // not MPI_Abort: that is the guard below
  std::_Exit(exit_code);  // MPI_Abort does not return; this keeps [[noreturn]] honest.
}

}  // namespace mpm_lig

//! The profiling-interface overrides described in mpi_session.h.
extern "C" int MPI_Finalize(void) {
  if (mpm_lig::g_orderly_shutdown)
    return PMPI_Finalize();
  std::string report = "an engine stopped the run (it called MPI_Finalize)";
  if (auto& reporter = mpm_lig::fatal_reporter())
    report += "\n" + reporter();
  mpm_lig::abort_job(report, mpm_lig::kExitEngineFailure);
}

//! Engines call MPI_Abort on their own communicator for errors found on one rank only
//! (`Error::one`). Report which instance failed and end the whole job with our exit code.
//! Other callers (no engine call in progress: the reporter says nothing) pass through.
extern "C" int MPI_Abort(MPI_Comm comm, int errorcode) {
  auto& reporter = mpm_lig::fatal_reporter();
  const std::string engine_report = reporter ? reporter() : std::string();
  if (engine_report.empty())
    return PMPI_Abort(comm, errorcode);
  mpm_lig::abort_job("an engine aborted the run (it called MPI_Abort)\n" + engine_report,
                     mpm_lig::kExitEngineFailure);
}
