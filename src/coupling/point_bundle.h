#pragma once

#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "io/bundle.h"
#include "rve/rve.h"

namespace mpm_lig::coupling {

//! A DEM point in a checkpoint: two members of its writer's bundle (io/bundle.h), the engine
//! restart (with the contact history), then the exact grain placement
//! (Rve::placement_file). The engines write and read restarts only through a path, so both
//! pass through a scratch file of the rank group (under the run's folder), copied into the
//! bundle or out of it. docs/hpc.md §3.

//! Members per point, and doubles per point in the index (two packed io::BundleMember).
constexpr std::size_t kPointMembers = 2;
constexpr std::size_t kPointIndexWidth = kPointMembers * io::kBundleMemberWidth;

//! Collective over a rank group: its RVEs' checkpoints into one bundle `folder/rank_<r>.bundle`,
//! written by the group's leader (r: its rank in the run).
class PointBundleWriter {
 public:
  //! `scratch`: the group's scratch folder (created here, removed by close()).
  PointBundleWriter(const std::string& folder, const std::string& scratch, int rank,
                    MPI_Comm group);
  ~PointBundleWriter();
  //! Checkpoint `rve` (Rve::write_checkpoint, collective over the group) into the bundle;
  //! its kPointIndexWidth index values go to `index` (zeros on the ranks that do not write).
  void add(rve::Rve& rve, std::vector<double>& index);
  //! Close the bundle (checked); the SHA-256 of the whole bundle on the leader, else "".
  std::string close();

 private:
  std::string scratch_;
  bool leader_ = false;
  MPI_Comm group_;
  std::unique_ptr<io::BundleWriter> bundle_;
};

//! Collective over a rank group: the point whose index values are `index` out of the bundles
//! in `folder` into the group's `scratch` folder, each member checked against its digest;
//! returns the restart file to hand to Rve::from_checkpoint. Throws naming the bundle, the
//! byte range and which member when a member cannot be read or has changed.
std::string unbundle_point(const std::string& folder, const double* index,
                           const std::string& scratch, MPI_Comm group);

//! Remove a group's scratch folder (its leader; after the last unbundle_point).
void remove_scratch(const std::string& scratch, MPI_Comm group);

}  // namespace mpm_lig::coupling
