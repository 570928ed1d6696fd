#pragma once

#include <string>

#include <mpi.h>

#include "mpm/case_spec.h"
#include "mpm/solver.h"

namespace mpm_lig::mpm {

//! What the Recorder must know to continue its files after a resume.
struct RecorderState {
  long history_rows = 0;               //!< data rows of history.csv (header excluded)
  double peak_bearing_pressure = 0.0;  //!< highest footing load / contact area so far [Pa]
  double largest_stiffened_cfl = 0.0;  //!< Solver::stiffened_cfl()'s largest value so far
};

//! Checkpoints of a run in `run_dir/checkpoints/` (names: CheckpointFolder):
//!
//!     step_<n>/mpm.h5          particle arrays (exact doubles), clock, footings, recorder
//!                              state, and what each material saves (Material::write_checkpoint)
//!                              as datasets and attributes named m<id>_...
//!     step_<n>/m<id>/          files of material <id> (a dem_rve: rank_<r>.bundle, one per
//!                              rank group, every RVE's engine restart with its contact
//!                              history and its exact placement, indexed in mpm.h5)
//!     step_<n>/case.json       the case it was written for (a resume compares)
//!     step_<n>/build           the build that wrote it
//!     step_<n>/MANIFEST.sha256 checksums of every file above (`sha256sum -c` reads it); a
//!                              bundle's comes from the rank that wrote it
//!     latest                   text: the name of the last complete step folder
//!
//! `latest` is replaced atomically (rename) after all ranks finished writing and the manifest
//! is written; the previous step folder is removed only then, so a kill at any moment leaves
//! one complete checkpoint. A failure on any rank ends the job (exit 1) and keeps the previous.
template <int D>
void write_checkpoint(const MpmCase& c, Solver<D>& solver, const RecorderState& recorder,
                      const std::string& run_dir, MPI_Comm comm);

//! Collective: overwrite a freshly built solver (and its materials) with the last checkpoint
//! of `run_dir`. Returns the recorder state saved with it.
template <int D>
RecorderState read_checkpoint(const MpmCase& c, Solver<D>& solver, const std::string& run_dir,
                              MPI_Comm comm);

//! Why the solver's materials cannot be checkpointed (state beyond their stress), or "".
template <int D>
std::string checkpoint_obstacle(const Solver<D>& solver);

//! Whether a checkpoint written now resumes bit-identically (Material::at_exact_checkpoint of
//! every material).
template <int D>
bool at_exact_checkpoint(const Solver<D>& solver);

}  // namespace mpm_lig::mpm
