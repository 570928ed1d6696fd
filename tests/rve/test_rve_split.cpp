// Two RVEs on two ranks (split communicators) give exactly the stresses of the same two RVEs
// run one after the other on one rank.
#include <gtest/gtest.h>

#include <mpi.h>

#include "core/case_node.h"
#include "rve/rve.h"
#include "test_rve_spec.h"

using namespace mpm_lig;

namespace {

rve::RveSpec spec_for(int seed) {
  nlohmann::json rve = test::small_rve_json();
  rve["grains"] = 80;
  rve["seed"] = seed;
  return test::parse_rve(rve);
}

//! Compress a fresh packing into contact, then shear it; returns the stress (Voigt).
Voigt6 drive(int seed, MPI_Comm comm) {
  auto r = rve::Rve::generate(spec_for(seed), comm, "RVE " + std::to_string(seed));
  Mat3 squeeze = Mat3::Identity() * (1.0 - 1e-3);
  squeeze(2, 2) = 1.0;
  for (int k = 0; k < 300 && mean_pressure(r->stress(), 2) < 5e4; ++k)
    r->deform(squeeze);
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 1e-3;
  for (int k = 0; k < 10; ++k)
    r->deform(shear);
  return to_voigt(r->stress());
}

}  // namespace

TEST(RveSplit, TwoRanksMatchOneRankExactly) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2);
  MPI_Comm own;
  MPI_Comm_split(MPI_COMM_WORLD, rank, 0, &own);
  const Voigt6 mine = drive(10 + rank, own);
  std::array<double, 12> both{};
  MPI_Gather(mine.data(), 6, MPI_DOUBLE, both.data(), 6, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (rank == 0) {
    for (int r = 0; r < 2; ++r) {
      const Voigt6 serial = drive(10 + r, own);
      EXPECT_LT(serial[0], 0.0);  // a loaded packing
      for (int i = 0; i < 6; ++i)
        EXPECT_EQ(both[6 * r + i], serial[i]) << "RVE " << r << " " << kVoigtNames[i];
    }
  }
  MPI_Comm_free(&own);
}
