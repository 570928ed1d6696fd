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
  owner_.resize(rve_count);
  for (std::size_t r = 0; r < rve_count; ++r)
    owner_[r] = static_cast<int>(r % static_cast<std::size_t>(groups_));
  index_groups();
}

void RveLayout::reassign(const std::vector<int>& owners) {
  if (owners.size() != rve_count_)
    throw std::invalid_argument("RveLayout::reassign: " + std::to_string(owners.size()) +
                                " owners for " + std::to_string(rve_count_) + " RVEs");
  for (const int g : owners) {
    if (g < 0 || g >= groups_)
      throw std::invalid_argument("RveLayout::reassign: no rank group " + std::to_string(g));
  }
  owner_ = owners;
  index_groups();
}

RveLayout::~RveLayout() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && group_comm_ != MPI_COMM_NULL)
    MPI_Comm_free(&group_comm_);
}

std::vector<std::size_t> RveLayout::owned(int group) const {
  std::vector<std::size_t> rves;
  for (std::size_t r = 0; r < rve_count_; ++r) {
    if (owner_[r] == group)
      rves.push_back(r);
  }
  return rves;
}

int RveLayout::owner(std::size_t rve) const {
  if (rve >= rve_count_)
    throw std::out_of_range("RVE index " + std::to_string(rve) + " out of range");
  return owner_[rve];
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
    counts[r] = static_cast<int>(group_sizes_[r / ranks_per_rve_] * w);
    offsets[r] = offset;
    offset += counts[r];
  }
  std::vector<double> by_group(rve_count_ * w);
  const int send = group_leader() ? static_cast<int>(owned_values.size()) : 0;
  MPI_Allgatherv(owned_values.data(), send, MPI_DOUBLE, by_group.data(), counts.data(),
                 offsets.data(), MPI_DOUBLE, world_);
  std::vector<double> all(rve_count_ * w);
  for (std::size_t k = 0; k < rve_count_; ++k)
    std::copy_n(&by_group[k * w], w, &all[by_group_order_[k] * w]);
  return all;
}

void RveLayout::index_groups() {
  owned_ = owned(group_);
  group_sizes_.assign(static_cast<std::size_t>(groups_), 0);
  for (const int g : owner_)
    ++group_sizes_[static_cast<std::size_t>(g)];
  by_group_order_.resize(rve_count_);
  for (std::size_t r = 0; r < rve_count_; ++r)
    by_group_order_[r] = r;
  std::stable_sort(by_group_order_.begin(), by_group_order_.end(),
                   [&](std::size_t a, std::size_t b) { return owner_[a] < owner_[b]; });
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
