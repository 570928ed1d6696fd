// General 3 x 3 fields (FieldWriter::add_matrix) and one point's history read back from a
// FieldWriter file (read_point_history): what a replay of a material point's path reads.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/field_writer.h"
#include "io/point_history.h"
#include "test_files.h"

namespace mpm_lig::io {
namespace {

using test_support::error_of;
using test_support::fresh_dir;

//! A non-symmetric F per point whose every entry differs and needs all 53 bits.
Mat3 deformation(std::size_t point, long step) {
  Mat3 F;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      F(i, j) = (i == j) + 1.0 / (3.0 + 7.0 * point + 11.0 * step + 3 * i + j);
  return F;
}

//! Steps 0, 1, 2 and then 5 (an output interval that is not one step) of three points.
void write_steps(const std::string& dir, const std::vector<long>& steps) {
  FieldWriter writer(dir);
  for (const long s : steps) {
    std::vector<Vec3> positions(3, Vec3::Zero());
    std::vector<Mat3> F(3);
    std::vector<double> scalar(3);
    for (std::size_t p = 0; p < 3; ++p) {
      F[p] = deformation(p, s);
      scalar[p] = 10.0 * s + p;
    }
    writer.begin_step(s, 0.25 * s, positions);
    writer.add_matrix("deformation_gradient", F);
    if (s != 5)
      writer.add_scalar("only_early", scalar);
    writer.end_step();
  }
}

TEST(PointHistory, MatricesReadBackBitForBitInStepOrder) {
  const std::string dir = fresh_dir("point_history", "steps");
  write_steps(dir, {0, 1, 2, 5});
  const PointHistory h =
      read_point_history(dir + "/results.h5", 2, {"deformation_gradient"}, {"only_early"});
  EXPECT_EQ(h.points, 3u);
  ASSERT_EQ(h.step, (std::vector<long>{0, 1, 2, 5}));
  EXPECT_EQ(h.time, (std::vector<double>{0.0, 0.25, 0.5, 1.25}));
  EXPECT_EQ(h.group.back(), "step_000005");
  for (std::size_t k = 0; k < h.step.size(); ++k) {
    const std::vector<double>& row = h.rows.at("deformation_gradient")[k];
    ASSERT_EQ(row.size(), 9u);
    const Mat3 F = deformation(2, h.step[k]);
    for (int c = 0; c < 9; ++c)
      EXPECT_EQ(row[c], F(c / 3, c % 3)) << "row-major component " << c;
    const std::vector<double>& early = h.rows.at("only_early")[k];
    if (h.step[k] == 5)
      EXPECT_TRUE(early.empty());
    else
      EXPECT_EQ(early, std::vector<double>{10.0 * h.step[k] + 2});
  }
}

TEST(PointHistory, XdmfNamesTheMatrixAsANineComponentTensorAndResumeKeepsIt) {
  const std::string dir = fresh_dir("point_history", "xdmf");
  write_steps(dir, {0, 1});
  std::stringstream text;
  text << std::ifstream(dir + "/results.xdmf").rdbuf();
  EXPECT_NE(text.str().find("Name=\"deformation_gradient\" AttributeType=\"Tensor\""),
            std::string::npos);
  EXPECT_NE(text.str().find("Dimensions=\"3 9\""), std::string::npos);
  // A resumed run rebuilds its index from the file: the n x 9 dataset must be known there.
  auto resumed = FieldWriter::resume(dir, "results", 1);
  ASSERT_EQ(resumed->steps_written(), 2u);
  resumed->begin_step(2, 0.5, std::vector<Vec3>(3, Vec3::Zero()));
  resumed->add_matrix("deformation_gradient", std::vector<Mat3>(3, Mat3::Identity()));
  resumed->end_step();
  EXPECT_EQ(read_point_history(dir + "/results.h5", 0, {"deformation_gradient"}).step.size(), 3u);
}

TEST(PointHistory, ProblemsAreNamed) {
  const std::string dir = fresh_dir("point_history", "problems");
  write_steps(dir, {0, 1});
  const std::string h5 = dir + "/results.h5";
  EXPECT_THROW(read_point_history(h5, 3, {"deformation_gradient"}), UnknownPointError);
  EXPECT_NE(error_of([&] {
              read_point_history(h5, 0, {"stress"});
            }).find("step_000000 has no dataset 'stress'"),
            std::string::npos);
  EXPECT_THROW(read_point_history(dir + "/absent.h5", 0, {}), PointHistoryError);
  std::ofstream(dir + "/text.h5") << "not hdf5\n";
  EXPECT_THROW(read_point_history(dir + "/text.h5", 0, {}), PointHistoryError);
  // Truncated: the superblock survives, the data does not.
  const auto size = std::filesystem::file_size(h5);
  std::filesystem::copy_file(h5, dir + "/cut.h5");
  std::filesystem::resize_file(dir + "/cut.h5", size / 3);
  EXPECT_THROW(read_point_history(dir + "/cut.h5", 0, {"deformation_gradient"}), PointHistoryError);
}

}  // namespace
}  // namespace mpm_lig::io
