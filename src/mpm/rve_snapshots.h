#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "mpm/case_spec.h"
#include "mpm/solver.h"

namespace mpm_lig::mpm {

//! Writes the RVE snapshots asked for in output.rve_snapshots: for each position, the DEM
//! point nearest to it in the reference configuration, into
//! DIR/snapshots/point_NNNNNN/rve_SSSSSS_{grains,contacts,cell}.vtk (SSSSSS the MPM step),
//! at the start, every `every` steps and at the end. Collective: every rank calls it, since
//! the point's RVE lives on whichever rank owns it.
template <int D>
class RveSnapshots {
 public:
  RveSnapshots(const RveSnapshotOutput& spec, const Solver<D>& solver, const std::string& directory,
               long total_steps);

  //! Collective: write the snapshots due after the solver's current step (a DEM material may
  //! create its RVEs for that, hence the mutable solver).
  void after_step(Solver<D>& solver);

  //! The material points chosen (one per requested position, in order).
  const std::vector<std::size_t>& points() const { return points_; }

 private:
  void write(Solver<D>& solver);

  std::string directory_;
  long every_, total_steps_;
  std::vector<std::size_t> points_;
};

}  // namespace mpm_lig::mpm
