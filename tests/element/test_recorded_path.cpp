// Recorded paths: the increments between recorded states, the CSV layout, the checks.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/case_node.h"
#include "element/path_csv.h"
#include "element/recorded_path.h"

namespace mpm_lig::element {
namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const std::string dir = std::string(MPM_LIG_BINARY_DIR) + "/test_output/recorded_path";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/" + name) << text;
  return dir + "/" + name;
}

Mat3 plane(double a, double b, double c, double d) {
  Mat3 F = Mat3::Identity();
  F.topLeftCorner<2, 2>() << a, b, c, d;
  return F;
}

TEST(RecordedPath, IncrementBetweenStatesRecoversTheIncrement) {
  const Mat3 F0 = plane(1.01, 0.2, -0.05, 0.97);
  const Mat3 dF = plane(0.999, 0.003, -0.001, 1.0004);
  const Mat3 got = increment_between(F0, dF * F0);
  EXPECT_LT((got - dF).cwiseAbs().maxCoeff(), 1e-15);
  // Plane states give an exactly plane increment: a 2D RVE refuses anything else.
  EXPECT_EQ(got(2, 2), 1.0);
  EXPECT_EQ(got(0, 2), 0.0);
  EXPECT_EQ(got(2, 1), 0.0);
  Mat3 G0, dG;
  G0 << 1.1, 0.1, 0.02, -0.03, 0.95, 0.04, 0.01, -0.02, 1.03;
  dG << 1.001, 0.002, -0.001, 0.0005, 0.998, 0.001, -0.002, 0.0003, 1.002;
  EXPECT_LT((increment_between(G0, dG * G0) - dG).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(RecordedPath, DiagonalStatesGiveTheirQuotientsExactly) {
  // A uniform biaxial path is diagonal: each component of ΔF is one correctly rounded quotient
  // (what the replay test relies on), not a product with a rounded inverse.
  const double a = 0.99980001999866669, b = 0.99960007998933451;
  const Mat3 got = increment_between(plane(a, 0, 0, a), plane(b, 0, 0, b));
  EXPECT_EQ(got(0, 0), b / a);
  EXPECT_EQ(got(1, 1), b / a);
  EXPECT_EQ(got(0, 1), 0.0);
}

TEST(RecordedPath, CsvColumnsByNameCommentsAndSubsteps) {
  const std::string file = write_file("ok.csv",
                                      "# a comment before the header\n"
                                      "substeps, F22 ,F21,F12,F11,time\n"
                                      "0,1,0,0,1,0\n"
                                      "\n"
                                      "25,0.99899999999999999911,0,0.001,1.0004,0.5\n"
                                      "0,0.998,0,0.002,1.0008,1\n");
  const RecordedPath path = read_path_csv(file);
  ASSERT_EQ(path.F.size(), 3u);
  EXPECT_EQ(path.label[1], "row 2 (line 5)");
  EXPECT_EQ(path.time[1], 0.5);
  EXPECT_EQ(path.F[1](1, 1), 0.999);
  EXPECT_EQ(path.F[1](0, 1), 0.001);
  EXPECT_EQ(path.F[2](0, 0), 1.0008);
  EXPECT_EQ(path.F[2](2, 2), 1.0);
  EXPECT_EQ(path.substeps, (std::vector<int>{25, 0}));
  EXPECT_FALSE(path.recorded_increment[0].has_value());
}

TEST(RecordedPath, CheckedThroughTheCaseWithTheRowNamed) {
  const std::string file = write_file("shear_3d.csv",
                                      "time,F11,F12,F13,F21,F22,F23,F31,F32,F33\n"
                                      "0,1,0,0,0,1,0,0,0,1\n"
                                      "1,1,0,0,0,1,0.01,0,0,1\n");
  const auto document = CaseDocument::parse(R"({"path": {"csv": ")" + file + R"("}})");
  const CaseNode node = document.root().child("path");
  EXPECT_EQ(read_recorded_path(node, 3)->intervals(), 1u);
  try {
    read_recorded_path(node, 2);
    FAIL() << "a 3D path was accepted for a 2D RVE";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.path(), "path.csv");
    EXPECT_NE(std::string(e.what()).find("row 2 (line 3): a 2D RVE takes plane deformation only"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mpm_lig::element
