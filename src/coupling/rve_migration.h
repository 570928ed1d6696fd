#pragma once

#include <memory>
#include <string>

#include <mpi.h>

#include "coupling/rve_state_fields.h"
#include "rve/rve.h"

namespace mpm_lig::coupling {

//! Moving a running RVE to another rank group: its checkpoint files (engine restart with the
//! contact history, and the exact grain placement) plus its Rve::State, which the groups
//! exchange by MPI. The new owner continues bit-identically to the RVE had it stayed (one
//! rank per RVE; docs/DESIGN.md §7 and §10).

// The state goes by MPI packed as rve_state_fields.h lists it (pack_state, unpack_state).

//! The leaving half (collective over the RVE's communicator): its files at `file`
//! (Rve::write_checkpoint, which leaves its arithmetic untouched), and its state.
rve::Rve::State send_rve(rve::Rve& rve, const std::string& file);
//! The arriving half (collective over `comm`): the RVE from `file` with `state`; rank 0 of
//! `comm` then removes the files.
std::unique_ptr<rve::Rve> receive_rve(const rve::RveSpec& spec, const std::string& file,
                                      const rve::Rve::State& state, MPI_Comm comm,
                                      const std::string& label);

}  // namespace mpm_lig::coupling
