#include <gtest/gtest.h>

#include <mpi.h>

#include "coupling/rve_layout.h"

using mpm_lig::Mat3;
using mpm_lig::coupling::RveLayout;

namespace {

int world_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

//! A tensor that encodes its RVE index, so a gather in the wrong order shows.
Mat3 tag(std::size_t rve) {
  return Mat3::Constant(static_cast<double>(rve)) + Mat3::Identity();
}

void check_layout(int ranks_per_rve, std::size_t rves) {
  RveLayout layout(MPI_COMM_WORLD, ranks_per_rve, rves);
  ASSERT_EQ(layout.groups(), world_size() / ranks_per_rve);
  // The groups' shares partition [0, rves), are balanced to within one RVE, and neighbours
  // in index (neighbours in space) belong to different groups.
  std::vector<int> owners(rves, -1);
  for (int g = 0; g < layout.groups(); ++g) {
    const std::vector<std::size_t> share = layout.owned(g);
    EXPECT_LE(share.size(), rves / layout.groups() + 1);
    EXPECT_GE(share.size(), rves / layout.groups());
    for (std::size_t i = 0; i < share.size(); ++i) {
      ASSERT_LT(share[i], rves);
      EXPECT_EQ(owners[share[i]], -1) << "RVE " << share[i] << " owned twice";
      owners[share[i]] = g;
      EXPECT_EQ(layout.owner(share[i]), g);
      if (i > 0) {
        EXPECT_LT(share[i - 1], share[i]);
      }
    }
  }
  for (std::size_t r = 0; r < rves; ++r) {
    EXPECT_GE(owners[r], 0) << "RVE " << r << " owned by nobody";
    if (r > 0 && layout.groups() > 1) {
      EXPECT_NE(owners[r], owners[r - 1]) << "RVEs " << r - 1 << " and " << r;
    }
  }
  int group_size = 0;
  MPI_Comm_size(layout.group_comm(), &group_size);
  EXPECT_EQ(group_size, ranks_per_rve);

  std::vector<Mat3> owned;
  for (const std::size_t r : layout.owned())
    owned.push_back(tag(r));
  const std::vector<Mat3> all = layout.gather(owned);
  ASSERT_EQ(all.size(), rves);
  for (std::size_t r = 0; r < rves; ++r)
    EXPECT_EQ(all[r], tag(r)) << "RVE " << r;
}

}  // namespace

TEST(RveLayout, OneRankPerRve) {
  check_layout(1, 7);
  check_layout(1, 1);
}

TEST(RveLayout, WholeWorldPerRve) {
  check_layout(world_size(), 5);
}

TEST(RveLayout, ReassignedRvesAreGatheredInRveOrder) {
  // Owners in an order unlike the dealt one (the last group gets RVEs 0 and 1, group 0 the
  // rest): a gather that kept the dealt order would put tags in the wrong places.
  const std::size_t rves = 9;
  RveLayout layout(MPI_COMM_WORLD, 1, rves);
  std::vector<int> owners(rves, 0);
  owners[0] = owners[1] = layout.groups() - 1;
  if (layout.groups() > 2)
    owners[7] = 1;
  layout.reassign(owners);
  EXPECT_EQ(layout.owners(), owners);
  std::vector<Mat3> owned;
  for (const std::size_t r : layout.owned()) {
    EXPECT_EQ(owners[r], layout.group());
    owned.push_back(tag(r));
  }
  const std::vector<Mat3> all = layout.gather(owned);
  for (std::size_t r = 0; r < rves; ++r)
    EXPECT_EQ(all[r], tag(r)) << "RVE " << r;
  owners[3] = layout.groups();
  EXPECT_THROW(layout.reassign(owners), std::invalid_argument);
  EXPECT_THROW(layout.reassign(std::vector<int>(rves - 1, 0)), std::invalid_argument);
}

TEST(RveLayout, MoreGroupsThanRves) {
  if (world_size() < 2)
    GTEST_SKIP() << "needs at least 2 ranks";
  check_layout(1, 1);
}

TEST(RveLayout, RefusesRanksPerRveThatDoNotDivide) {
  EXPECT_THROW(RveLayout(MPI_COMM_WORLD, world_size() + 1, 3), std::runtime_error);
}
