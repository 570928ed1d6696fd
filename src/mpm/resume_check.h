#pragma once

#include <string>

#include <mpi.h>

#include "mpm/case_spec.h"

namespace mpm_lig::mpm {

//! Collective: refuse to resume `run_dir` (ResumeError on every rank, exit 2) when the result
//! could be wrong or earlier results could be lost. Checked on rank 0, before any file is
//! touched or any packing made:
//!  - no name in `run_dir` leads out of it (io::check_run_folder);
//!  - `checkpoints/latest` names a plain step folder that exists;
//!  - every file of that checkpoint matches its MANIFEST.sha256 (a bundle: every member
//!    matches the SHA-256 of the index, checked by all ranks, each a share of the members);
//!  - the case differs from the checkpoint's case.json in safe keys only (the others named);
//!  - the saved state is finite, and end.steps / end.time is not before the checkpoint;
//!  - history.csv holds at least the checkpoint's rows and results.h5 (if any) can be read.
void check_resume(const MpmCase& c, const std::string& run_dir, MPI_Comm comm);

}  // namespace mpm_lig::mpm
