#include <gtest/gtest.h>

#include "coupling/dem_work.h"

namespace mpm_lig::coupling {
namespace {

Mat3 stretch(double e) {
  Mat3 dF = Mat3::Identity();
  dF(0, 0) += e;
  return dF;
}

// 100 grains, cap 50 sub-steps, preparation at 100 kPa: "low" is below 10 kPa, "quiet" below
// |dF - 1| = 1e-5. Each update books sub-steps x grains to the point and to every class it is in.
TEST(DemWork, BooksEachUpdateToItsPointAndClasses) {
  DemWork w;
  w.start(3, 100.0, 50, 1e5);
  w.add(0, 50, 2e5, stretch(1e-3));  // at the cap
  w.add(1, 20, 9e3, stretch(1e-3));  // low mean stress
  w.add(1, 30, 1e4, stretch(1e-3));  // exactly 10 %: not low
  w.add(2, 10, 1e5, stretch(9e-6));  // quiet
  w.add(2, 10, 1e5, stretch(2e-5));  // not quiet
  EXPECT_EQ(w.total(0), 5000.0);
  EXPECT_EQ(w.total(1), 5000.0);
  EXPECT_EQ(w.total(2), 2000.0);
  EXPECT_EQ(w.sum(0), 12000.0);
  EXPECT_EQ(w.sum(1), 5000.0);
  EXPECT_EQ(w.sum(2), 2000.0);
  EXPECT_EQ(w.sum(3), 1000.0);
}

TEST(DemWork, NoCapMeansNothingAtTheCap) {
  DemWork w;
  w.start(1, 10.0, 0, 1e5);
  w.add(0, 100000, 1e5, stretch(1e-2));
  EXPECT_EQ(w.sum(1), 0.0);
  EXPECT_EQ(w.total(0), 1e6);
}

TEST(DemWork, RowsRoundTrip) {
  DemWork a, b;
  a.start(2, 100.0, 50, 1e5);
  b.start(2, 100.0, 50, 1e5);
  a.add(1, 50, 1e3, stretch(1e-6));
  b.restore_row(1, a.row(1));
  for (int k = 0; k < DemWork::kValues; ++k)
    EXPECT_EQ(b.sum(k), a.sum(k));
  EXPECT_EQ(b.sum(1), 5000.0);  // the one update was at the cap, low and quiet at once
  EXPECT_EQ(b.sum(2), 5000.0);
  EXPECT_EQ(b.sum(3), 5000.0);
}

}  // namespace
}  // namespace mpm_lig::coupling
