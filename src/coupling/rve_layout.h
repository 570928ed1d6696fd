#pragma once

#include <cstddef>
#include <vector>

#include <mpi.h>

#include "core/tensor.h"

namespace mpm_lig::coupling {

//! Which ranks run which RVEs.
//!
//! The ranks of `world` form groups of `ranks_per_rve` consecutive ranks; each group has its
//! own communicator (every RVE of the group runs on it). RVEs start dealt to the groups like
//! cards: RVE i belongs to group i mod groups. Material points are numbered in space, so the
//! expensive ones (under a footing, in a shear band) sit next to each other; dealt out, they
//! spread over all ranks instead of loading the one that would own their block. A balancer
//! may then move RVEs (reassign(), the same owners given on every rank). The MPM
//! itself is replicated on every rank, so after each update the owners' stresses are
//! gathered to everyone, in RVE order: the result does not depend on the number of ranks as
//! long as one RVE's own computation does not (one rank per RVE). docs/DESIGN.md §7.
class RveLayout {
 public:
  //! Collective over `world`. `ranks_per_rve` must divide the size of `world`.
  RveLayout(MPI_Comm world, int ranks_per_rve, std::size_t rve_count);
  ~RveLayout();
  RveLayout(const RveLayout&) = delete;
  RveLayout& operator=(const RveLayout&) = delete;

  MPI_Comm world() const { return world_; }
  //! The communicator of this rank's group: the one its RVEs run on.
  MPI_Comm group_comm() const { return group_comm_; }
  int group() const { return group_; }
  int groups() const { return groups_; }
  bool group_leader() const { return group_rank_ == 0; }

  std::size_t rve_count() const { return rve_count_; }
  //! The RVE indices `group` owns, ascending (this rank's group by default).
  std::vector<std::size_t> owned(int group) const;
  const std::vector<std::size_t>& owned() const { return owned_; }
  bool owns(std::size_t rve) const { return owner(rve) == group_; }
  //! The group that owns RVE `rve`.
  int owner(std::size_t rve) const;
  //! Every RVE's group, in RVE order (the same on every rank).
  const std::vector<int>& owners() const { return owner_; }
  //! Give RVE i to group `owners[i]`: every rank must pass the same owners.
  void reassign(const std::vector<int>& owners);

  //! Collective: `owned` holds one tensor per RVE this group owns (in the order of `owned()`);
  //! returns the tensors of all RVEs in RVE order, identical on every rank.
  std::vector<Mat3> gather(const std::vector<Mat3>& owned) const;
  //! The same for `width` doubles per RVE.
  std::vector<double> gather(const std::vector<double>& owned, int width) const;

 private:
  void index_groups();

  MPI_Comm world_;
  MPI_Comm group_comm_ = MPI_COMM_NULL;
  int world_rank_ = 0;
  int world_size_ = 1;
  int ranks_per_rve_ = 1;
  int group_ = 0;
  int groups_ = 1;
  int group_rank_ = 0;
  std::size_t rve_count_ = 0;
  std::vector<int> owner_;  //!< every RVE's group
  std::vector<std::size_t> owned_;
  std::vector<std::size_t> group_sizes_;     //!< RVEs per group
  std::vector<std::size_t> by_group_order_;  //!< RVEs group by group, ascending in each
};

}  // namespace mpm_lig::coupling
