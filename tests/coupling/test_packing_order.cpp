// Which of K packings each point is cloned from. Cyclic: point i from packing i mod K, so on a
// row-major grid of 48 points a row neighbouring columns never share a packing (the
// shortest-wave imperfection of docs/methods.md §7). Scattered: every packing about equally
// often, and neighbours along a row or a column share a packing about as often as chance says.
#include <cstddef>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "coupling/packings.h"

namespace mpm_lig::coupling {
namespace {

constexpr std::size_t kRow = 48, kRows = 48;

//! The share of neighbouring pairs (along x, then along y) cloned from the same packing.
std::pair<double, double> shared_by_neighbours(const PackingOrder& order) {
  std::size_t along_x = 0, along_y = 0;
  for (std::size_t j = 0; j < kRows; ++j) {
    for (std::size_t i = 0; i < kRow; ++i) {
      const std::size_t p = i + kRow * j;
      if (i + 1 < kRow && order.of(p) == order.of(p + 1))
        ++along_x;
      if (j + 1 < kRows && order.of(p) == order.of(p + kRow))
        ++along_y;
    }
  }
  const double pairs = static_cast<double>((kRow - 1) * kRows);
  return {along_x / pairs, along_y / pairs};
}

TEST(PackingOrder, CyclicAlternatesTheColumns) {
  const PackingOrder cyclic{2, false};
  for (std::size_t p = 0; p < 100; ++p)
    EXPECT_EQ(cyclic.of(p), p % 2);
  const auto [x, y] = shared_by_neighbours(cyclic);
  EXPECT_EQ(x, 0.0);
  EXPECT_EQ(y, 1.0);
}

TEST(PackingOrder, ScatteredDrawsEveryPackingAndMixesNeighbours) {
  for (const std::size_t k : {2u, 3u, 7u}) {
    const PackingOrder scattered{k, true};
    std::vector<std::size_t> count(k, 0);
    for (std::size_t p = 0; p < kRow * kRows; ++p) {
      const std::size_t q = scattered.of(p);
      ASSERT_LT(q, k);
      EXPECT_EQ(q, scattered.of(p));  // a function of the index alone
      ++count[q];
    }
    const double expected = static_cast<double>(kRow * kRows) / k;
    for (const std::size_t c : count)
      EXPECT_NEAR(c / expected, 1.0, 0.1) << k;
    const auto [x, y] = shared_by_neighbours(scattered);
    EXPECT_NEAR(x, 1.0 / k, 0.05) << k;
    EXPECT_NEAR(y, 1.0 / k, 0.05) << k;
  }
}

TEST(PackingOrder, ScatteredIsTheSameOnEveryMachine) {
  // Fixed values of the hash: a change of it would change every scattered run.
  const PackingOrder scattered{5, true};
  std::size_t first[8];
  for (std::size_t p = 0; p < 8; ++p)
    first[p] = scattered.of(p);
  const std::size_t expected[8] = {0, 0, 0, 3, 3, 3, 2, 2};
  for (std::size_t p = 0; p < 8; ++p)
    EXPECT_EQ(first[p], expected[p]) << p;
}

}  // namespace
}  // namespace mpm_lig::coupling
