#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/tensor.h"
#include "io/csv_history.h"

using namespace mpm_lig;

TEST(Voigt, RoundTripsAndUsesLammpsOrder) {
  Mat3 t;
  t << 1, 4, 5, 4, 2, 6, 5, 6, 3;
  const Voigt6 v = to_voigt(t);
  EXPECT_EQ(v, (Voigt6{1, 2, 3, 4, 5, 6}));
  EXPECT_TRUE(from_voigt(v).isApprox(t));
}

TEST(Invariants, HydrostaticAndUniaxial) {
  EXPECT_DOUBLE_EQ(mean_pressure(-100.0 * Mat3::Identity()), 100.0);
  EXPECT_NEAR(deviatoric_stress(-100.0 * Mat3::Identity()), 0.0, 1e-12);
  Mat3 uniaxial = Mat3::Zero();
  uniaxial(0, 0) = -30.0;
  EXPECT_NEAR(deviatoric_stress(uniaxial), 30.0, 1e-12);
}

TEST(Invariants, InPlaneForDiscPackings) {
  Mat3 sigma = Mat3::Zero();
  sigma(0, 0) = -300.0;
  sigma(1, 1) = -100.0;
  sigma(0, 1) = sigma(1, 0) = 50.0;
  sigma(2, 2) = -7.0;  // out of plane: ignored in 2D
  EXPECT_DOUBLE_EQ(mean_pressure(sigma, 2), 200.0);
  EXPECT_DOUBLE_EQ(deviatoric_stress(sigma, 2), std::hypot(100.0, 50.0));
  EXPECT_DOUBLE_EQ(mean_pressure(sigma, 3), mean_pressure(sigma));
}

TEST(HenckyStrain, LogOfPrincipalStretchesAndFiniteWhenDegenerate) {
  const Mat3 stretch = Vec3(2.0, 1.0, 0.5).asDiagonal();
  const Mat3 q = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  // A rotation after the stretch (F = Q U) leaves ln V = Q ln U Qᵀ.
  const Mat3 expected = q * Vec3(std::log(2.0), 0.0, std::log(0.5)).asDiagonal() * q.transpose();
  EXPECT_TRUE(hencky_strain(q * stretch).isApprox(expected, 1e-12));
  EXPECT_NEAR(deviatoric_strain(hencky_strain(Mat3::Identity() * 1.1)), 0.0, 1e-14);
  EXPECT_TRUE(hencky_strain(Mat3::Zero()).allFinite());
}

TEST(CsvHistory, WritesHeaderAndExactRows) {
  const std::string file = ::testing::TempDir() + "/history_test.csv";
  {
    io::CsvHistory h(file, {"a", "b"});
    h.write({0.1, 1.0 / 3.0});
    EXPECT_THROW(h.write({1.0}), std::invalid_argument);
  }
  std::ifstream in(file);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(header, "a,b");
  double a = 0, b = 0;
  ASSERT_EQ(std::sscanf(row.c_str(), "%lf,%lf", &a, &b), 2);
  EXPECT_EQ(a, 0.1);
  EXPECT_EQ(b, 1.0 / 3.0);
}
