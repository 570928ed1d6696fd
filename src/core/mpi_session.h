#pragma once

#include <functional>
#include <string>

namespace mpm_lig {

//! MPI for the life of main(): MPI_Init in the constructor, MPI_Finalize in the destructor.
//!
//! Why more than that: both DEM engines end a run on error with `MPI_Finalize(); exit(1)`
//! on their own communicator, which leaves every other rank waiting forever. This file
//! defines MPI_Finalize in the executable (MPI profiling interface, forwarding to
//! PMPI_Finalize). A call that does not come from this session's destructor is an engine
//! dying in mid-run: we report it (see `set_fatal_reporter`) and call MPI_Abort on
//! MPI_COMM_WORLD, so the whole job ends at once with a non-zero code. MPI_Abort is guarded
//! the same way: engines call it on their own communicator for errors found on one rank, and
//! it then says which instance failed (docs/DESIGN.md §3.5).
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0;
  int size_ = 1;
};

//! Exit code of a job ended by an engine error caught in MPI_Finalize.
inline constexpr int kExitEngineFailure = 3;

//! Called (on the failing rank) when an engine ends the process; returns the text to print:
//! which RVE, which rank, the engine's last output, or "" when no engine call is in progress
//! (an MPI_Abort from elsewhere then passes through unchanged). Set by the DEM layer.
void set_fatal_reporter(std::function<std::string()> reporter);

//! End the whole job now from any rank: print `message` on stderr and MPI_Abort.
[[noreturn]] void abort_job(const std::string& message, int exit_code);

}  // namespace mpm_lig
