#include "coupling/rve_layout.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace mpm_lig::coupling {

RveLayout::RveLayout(MPI_Comm world, int ranks_per_rve, std::size_t rve_count)
    : world_(world), ranks_per_rve_(ranks_per_rve), rve_count_(rve_count) {
  MPI_Comm_rank(world, &world_rank_);
  MPI_Comm_size(world, &world_size_);
  if (ranks_per_rve < 1 || world_size_ % ranks_per_rve != 0) {
    throw std::runtime_error("ranks_per_rve = " + std::to_string(ranks_per_rve) +
                             " does not divide the " + std::to_string(world_size_) +
                             " MPI ranks of this run");
  }
  groups_ = world_size_ / ranks_per_rve;
  group_ = world_rank_ / ranks_per_rve;
  MPI_Comm_split(world, group_, world_rank_, &group_comm_);
  MPI_Comm_rank(group_comm_, &group_rank_);
  owned_ = owned(group_);
}

RveLayout::~RveLayout() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && group_comm_ != MPI_COMM_NULL)
    MPI_Comm_free(&group_comm_);
}

std::vector<std::size_t> RveLayout::owned(int group) const {
  std::vector<std::size_t> rves;
  for (std::size_t r = static_cast<std::size_t>(group); r < rve_count_;
       r += static_cast<std::size_t>(groups_))
    rves.push_back(r);
  return rves;
}

int RveLayout::owner(std::size_t rve) const {
  if (rve >= rve_count_)
    throw std::out_of_range("RVE index " + std::to_string(rve) + " out of range");
  return static_cast<int>(rve % static_cast<std::size_t>(groups_));
}

std::size_t RveLayout::local_index(std::size_t rve) const {
  if (!owns(rve))
    throw std::logic_error("RVE " + std::to_string(rve) + " is not owned by group " +
                           std::to_string(group_));
  return rve / static_cast<std::size_t>(groups_);
}

std::vector<double> RveLayout::gather(const std::vector<double>& owned_values, int width) const {
  const std::size_t w = static_cast<std::size_t>(width);
  if (owned_values.size() != owned_.size() * w) {
    throw std::invalid_argument("RveLayout::gather: " + std::to_string(owned_values.size()) +
                                " values for " + std::to_string(owned_.size() * w) + " expected");
  }
  // Only group leaders contribute, so each RVE's values appear exactly once: group by group,
  // in rank order. They are then dealt back into RVE order.
  std::vector<int> counts(world_size_, 0), offsets(world_size_, 0);
  int offset = 0;
  for (int r = 0; r < world_size_; r += ranks_per_rve_) {
    counts[r] = static_cast<int>(owned(r / ranks_per_rve_).size() * w);
    offsets[r] = offset;
    offset += counts[r];
  }
  std::vector<double> by_group(rve_count_ * w);
  const int send = group_leader() ? static_cast<int>(owned_values.size()) : 0;
  MPI_Allgatherv(owned_values.data(), send, MPI_DOUBLE, by_group.data(), counts.data(),
                 offsets.data(), MPI_DOUBLE, world_);
  std::vector<double> all(rve_count_ * w);
  std::size_t next = 0;
  for (int g = 0; g < groups_; ++g) {
    for (const std::size_t rve : owned(g)) {
      std::copy_n(&by_group[next], w, &all[rve * w]);
      next += w;
    }
  }
  return all;
}

std::vector<Mat3> RveLayout::gather(const std::vector<Mat3>& owned) const {
  std::vector<double> flat;
  flat.reserve(owned.size() * 9);
  for (const Mat3& m : owned)
    flat.insert(flat.end(), m.data(), m.data() + 9);
  const std::vector<double> all = gather(flat, 9);
  std::vector<Mat3> out(rve_count_);
  for (std::size_t i = 0; i < rve_count_; ++i)
    out[i] = Eigen::Map<const Mat3>(&all[9 * i]);
  return out;
}

}  // namespace mpm_lig::coupling
