// GoogleTest main for every mpm_lig test: MPI up for the whole run (MPI tests run the same
// binary on every rank; each rank reports, so a failure on rank 1 is not hidden).
#include <gtest/gtest.h>

#include "core/mpi_session.h"

int main(int argc, char** argv) {
  mpm_lig::MpiSession mpi(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
