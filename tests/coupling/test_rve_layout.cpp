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
  // The groups' blocks partition [0, rves) and are balanced to within one RVE.
  EXPECT_EQ(layout.first(0), 0u);
  EXPECT_EQ(layout.last(layout.groups() - 1), rves);
  for (int g = 0; g < layout.groups(); ++g) {
    const std::size_t n = layout.last(g) - layout.first(g);
    EXPECT_LE(n, rves / layout.groups() + 1);
    EXPECT_GE(n, rves / layout.groups());
    for (std::size_t r = layout.first(g); r < layout.last(g); ++r)
      EXPECT_EQ(layout.owner(r), g);
  }
  int group_size = 0;
  MPI_Comm_size(layout.group_comm(), &group_size);
  EXPECT_EQ(group_size, ranks_per_rve);

  std::vector<Mat3> owned;
  for (std::size_t r = layout.first(); r < layout.last(); ++r)
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

TEST(RveLayout, MoreGroupsThanRves) {
  if (world_size() < 2)
    GTEST_SKIP() << "needs at least 2 ranks";
  check_layout(1, 1);
}

TEST(RveLayout, RefusesRanksPerRveThatDoNotDivide) {
  EXPECT_THROW(RveLayout(MPI_COMM_WORLD, world_size() + 1, 3), std::runtime_error);
}
