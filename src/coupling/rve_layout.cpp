#include "coupling/rve_layout.h"

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
}

RveLayout::~RveLayout() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && group_comm_ != MPI_COMM_NULL)
    MPI_Comm_free(&group_comm_);
}

std::size_t RveLayout::first(int group) const {
  return rve_count_ * static_cast<std::size_t>(group) / static_cast<std::size_t>(groups_);
}

std::size_t RveLayout::last(int group) const {
  return first(group + 1);
}

int RveLayout::owner(std::size_t rve) const {
  for (int g = 0; g < groups_; ++g) {
    if (rve < last(g))
      return g;
  }
  throw std::out_of_range("RVE index " + std::to_string(rve) + " out of range");
}

std::vector<double> RveLayout::gather(const std::vector<double>& owned, int width) const {
  const std::size_t mine = (last() - first()) * static_cast<std::size_t>(width);
  if (owned.size() != mine) {
    throw std::invalid_argument("RveLayout::gather: " + std::to_string(owned.size()) +
                                " values for " + std::to_string(mine) + " expected");
  }
  // Only group leaders contribute, so each RVE's values appear exactly once, in rank order,
  // which is RVE order because groups own consecutive blocks.
  std::vector<int> counts(world_size_, 0), offsets(world_size_, 0);
  for (int r = 0; r < world_size_; ++r) {
    if (r % ranks_per_rve_ != 0)
      continue;
    const int g = r / ranks_per_rve_;
    counts[r] = static_cast<int>((last(g) - first(g)) * static_cast<std::size_t>(width));
    offsets[r] = static_cast<int>(first(g) * static_cast<std::size_t>(width));
  }
  std::vector<double> all(rve_count_ * static_cast<std::size_t>(width));
  const int send = group_leader() ? static_cast<int>(owned.size()) : 0;
  MPI_Allgatherv(owned.data(), send, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, world_);
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
