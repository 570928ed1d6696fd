#pragma once

#include <string>
#include <vector>

#include <mpi.h>

#include "dem/engine.h"

namespace mpm_lig::rve {

//! The grains' positions and periodic image flags bit for bit, ordered by grain id.
//!
//! An engine's write_restart wraps every grain into the cell through the cell's reduced
//! coordinates (x → λ → x), which changes positions at round-off; the file holds the changed
//! ones. A checkpoint keeps the exact ones beside the restart file and puts them back in the
//! writer and in the reader, so that writing and resuming leave the arithmetic untouched
//! (docs/DESIGN.md §10).
struct Placement {
  std::vector<double> x;   //!< 3 per grain
  std::vector<int> image;  //!< 1 per grain (the engine's packed image flags)
};

//! What `engine` holds now.
Placement take_placement(dem::Engine& engine);
//! Put `placement` back into `engine` (same grains).
void put_placement(dem::Engine& engine, const Placement& placement);

//! Write `placement` to `file` from rank 0 of `comm`, then check its size on every rank
//! (throws on every rank when the write did not reach the disk).
void write_placement(const Placement& placement, const std::string& file, MPI_Comm comm);
//! Read a placement of `grains` grains; throws naming the file when it is missing, of
//! another size or of another layout.
Placement read_placement(const std::string& file, long grains);

}  // namespace mpm_lig::rve
