#pragma once

#include <stdexcept>
#include <string>

#include <mpi.h>

namespace mpm_lig {

//! SIGTERM (the end of a batch job's wall time), SIGINT (Ctrl-C) and SIGHUP (the terminal of
//! an interactive run closed) only set a flag, from the start of the program: every phase of
//! a run (packing preparation, gravity stage, stepping, an element test's increments) polls
//! it where all ranks of a communicator agree, and stops cleanly (exit 4) saying what was
//! and was not written. Installed by main() before anything else happens.
void install_stop_handlers();

//! Whether this process has received a stop signal (no communication).
bool stop_signal_received();

//! Collective over `comm`: whether any of its ranks has received a stop signal.
bool stop_requested(MPI_Comm comm);

//! Thrown on every rank of the run alike once they agree to stop before the run is complete;
//! `what()` says where the run stopped and what is on disk. The application prints it and
//! exits with kExitStopped.
class StopRequested : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mpm_lig
