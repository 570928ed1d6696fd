#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <hdf5.h>

#include "io/field_writer.h"

namespace mpm_lig::io {
namespace {

std::string output_dir(const std::string& name) {
  const std::string dir = std::string(MPM_LIG_BINARY_DIR) + "/test_output/" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

std::string read_text(const std::string& filename) {
  std::ifstream in(filename);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

//! Reads datasets and attributes back through the HDF5 C API, independently of the writer.
class H5Reader {
 public:
  explicit H5Reader(const std::string& filename)
      : file_(H5Fopen(filename.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~H5Reader() {
    if (file_ >= 0)
      H5Fclose(file_);
  }
  bool ok() const { return file_ >= 0; }
  bool exists(const std::string& path) const {
    // Check each level: H5Lexists needs the parent to exist.
    std::string partial;
    std::stringstream parts(path);
    std::string part;
    while (std::getline(parts, part, '/')) {
      if (part.empty())
        continue;
      partial += "/" + part;
      if (H5Lexists(file_, partial.c_str(), H5P_DEFAULT) <= 0)
        return false;
    }
    return true;
  }
  std::vector<hsize_t> shape(const std::string& path) const {
    const hid_t d = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    const hid_t s = H5Dget_space(d);
    std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(s));
    H5Sget_simple_extent_dims(s, dims.data(), nullptr);
    H5Sclose(s);
    H5Dclose(d);
    return dims;
  }
  template <class T>
  std::vector<T> read(const std::string& path, hid_t mem_type) const {
    std::size_t count = 1;
    for (const hsize_t n : shape(path))
      count *= n;
    std::vector<T> out(count);
    const hid_t d = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    EXPECT_GE(H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0) << path;
    H5Dclose(d);
    return out;
  }
  double time_of(const std::string& group) const {
    double t = -1.0;
    const hid_t a = H5Aopen_by_name(file_, group.c_str(), "time", H5P_DEFAULT, H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_DOUBLE, &t);
    H5Aclose(a);
    return t;
  }

 private:
  hid_t file_;
};

//! Tags open and close in proper nesting (a well-formedness check of the XDMF structure).
bool tags_balanced(const std::string& xml, std::string& problem) {
  std::vector<std::string> stack;
  const std::regex tag(R"(<(/?)([A-Za-z_][\w.-]*)[^>]*?(/?)>)");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), tag); it != std::sregex_iterator();
       ++it) {
    const std::string name = (*it)[2];
    if ((*it)[3] == "/")
      continue;
    if ((*it)[1] == "/") {
      if (stack.empty() || stack.back() != name) {
        problem = "unexpected </" + name + ">";
        return false;
      }
      stack.pop_back();
    } else {
      stack.push_back(name);
    }
  }
  if (!stack.empty())
    problem = "<" + stack.back() + "> not closed";
  return stack.empty();
}

std::vector<Vec3> positions_2d_as_3d(const std::vector<Eigen::Vector2d>& p) {
  std::vector<Vec3> out;
  for (const auto& q : p)
    out.emplace_back(q.x(), q.y(), 0.0);
  return out;
}

TEST(FieldWriter, TwoStepsReadBackWithTheHdf5Api) {
  const std::string dir = output_dir("two_steps");
  std::vector<Eigen::Vector2d> pos = {{0.0, 1.0}, {2.0, 3.0}, {4.5, -1.25}};
  const std::vector<double> mass = {1.0, 2.0, 3.0};
  const std::vector<Eigen::Vector2d> vel = {{1.0, -1.0}, {0.5, 0.25}, {0.0, 2.0}};
  std::vector<Voigt6> stress = {{1, 2, 3, 4, 5, 6}, {7, 8, 9, 10, 11, 12}, {-1, -2, -3, 0, 0, 0}};
  const std::vector<int> ids = {0, 1, 7};
  {
    FieldWriter writer(dir);
    writer.begin_step(0, 0.0, pos);
    writer.add_scalar("mass", mass);
    writer.add_vector("velocity", vel);
    writer.add_tensor("stress", stress);
    writer.add_int("material", ids);
    writer.end_step();
    pos[1].x() = 2.5;
    stress[2][3] = -4.0;
    writer.begin_step(120, 0.375, pos);
    writer.add_tensor("stress", stress);
    writer.add_int("material", ids);
    writer.end_step();
    EXPECT_EQ(writer.steps_written(), 2u);
  }
  H5Reader h5(dir + "/results.h5");
  ASSERT_TRUE(h5.ok());
  EXPECT_DOUBLE_EQ(h5.time_of("/step_000000"), 0.0);
  EXPECT_DOUBLE_EQ(h5.time_of("/step_000120"), 0.375);
  EXPECT_EQ(h5.shape("/step_000000/positions"), (std::vector<hsize_t>{3, 3}));
  EXPECT_EQ(h5.shape("/step_000000/mass"), (std::vector<hsize_t>{3}));
  EXPECT_EQ(h5.shape("/step_000000/stress"), (std::vector<hsize_t>{3, 6}));
  EXPECT_FALSE(h5.exists("/step_000120/mass"));

  const auto xyz = h5.read<double>("/step_000120/positions", H5T_NATIVE_DOUBLE);
  const auto expected = positions_2d_as_3d(pos);
  for (std::size_t i = 0; i < pos.size(); ++i)
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(xyz[3 * i + d], expected[i][d]);
  EXPECT_EQ(h5.read<double>("/step_000000/mass", H5T_NATIVE_DOUBLE), mass);
  const auto v = h5.read<double>("/step_000000/velocity", H5T_NATIVE_DOUBLE);
  EXPECT_EQ(v, (std::vector<double>{1, -1, 0, 0.5, 0.25, 0, 0, 2, 0}));
  const auto s = h5.read<double>("/step_000120/stress", H5T_NATIVE_DOUBLE);
  for (std::size_t i = 0; i < stress.size(); ++i)
    for (int c = 0; c < 6; ++c)
      EXPECT_EQ(s[6 * i + c], stress[i][c]);
  EXPECT_EQ(h5.read<int>("/step_000120/material", H5T_NATIVE_INT), ids);
}

TEST(FieldWriter, XdmfIsWellFormedAndPointsAtExistingDatasets) {
  const std::string dir = output_dir("xdmf");
  {
    FieldWriter writer(dir, "fields");
    for (long step : {0L, 10L}) {
      const std::vector<Vec3> pos = {{0, 0, 0}, {1, 0, 0}};
      writer.begin_step(step, 1e-3 * step, pos);
      writer.add_scalar("volume", {1.0, 1.0});
      writer.add_tensor("strain", std::vector<Mat3>(2, Mat3::Identity()));
      writer.end_step();
      // After each step the index must already describe everything written so far.
      const std::string xml = read_text(dir + "/fields.xdmf");
      std::string problem;
      EXPECT_TRUE(tags_balanced(xml, problem)) << problem;
    }
  }
  const std::string xml = read_text(dir + "/fields.xdmf");
  EXPECT_NE(xml.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(xml.find("<Time Value=\"0.01\"/>"), std::string::npos);
  EXPECT_NE(xml.find("TopologyType=\"Polyvertex\" NumberOfElements=\"2\""), std::string::npos);
  H5Reader h5(dir + "/fields.h5");
  ASSERT_TRUE(h5.ok());
  const std::regex ref(R"(fields\.h5:(/[^<]+)<)");
  int references = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), ref); it != std::sregex_iterator();
       ++it, ++references)
    EXPECT_TRUE(h5.exists((*it)[1])) << (*it)[1];
  // Per step: positions, volume, and the strain tensor referenced once per Tensor6 column.
  EXPECT_EQ(references, 2 * (1 + 1 + 6));
}

TEST(FieldWriter, AKilledRunKeepsItsCompletedSteps) {
  const std::string dir = output_dir("killed");
  const std::vector<Vec3> pos(20000, Vec3(1.0, 2.0, 3.0));
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    FieldWriter writer(dir);
    for (long step = 0; step < 3; ++step) {
      writer.begin_step(step, 0.1 * step, pos);
      writer.add_scalar("volume", std::vector<double>(pos.size(), 1.0 + step));
      if (step < 2)
        writer.end_step();
    }
    _exit(0);  // killed in the middle of step 2: no end_step, no destructors
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  H5Reader h5(dir + "/results.h5");
  ASSERT_TRUE(h5.ok());
  EXPECT_EQ(h5.read<double>("/step_000001/volume", H5T_NATIVE_DOUBLE),
            std::vector<double>(pos.size(), 2.0));
  const std::string xml = read_text(dir + "/results.xdmf");
  EXPECT_NE(xml.find("step_000001"), std::string::npos);
  EXPECT_EQ(xml.find("step_000002"), std::string::npos);
}

TEST(FieldWriter, ResumeKeepsEarlierStepsInTheIndex) {
  const std::string dir = output_dir("resume");
  const std::vector<Vec3> pos = {{0, 0, 0}, {1, 0, 0}};
  auto write_step = [&](FieldWriter& writer, long step, double volume) {
    writer.begin_step(step, 1e-3 * step, pos);
    writer.add_scalar("volume", {volume, volume});
    writer.add_vector("velocity", std::vector<Vec3>(2, Vec3(1, 2, 3)));
    writer.add_tensor("strain", std::vector<Mat3>(2, Mat3::Identity()));
    writer.add_int("material", {0, 1});
    writer.end_step();
  };
  {
    FieldWriter first(dir, "fields");
    for (long step : {0L, 10L, 20L})
      write_step(first, step, 1.0);
  }
  // A run resumed from its step-10 checkpoint writes step 20 again.
  auto resumed = FieldWriter::resume(dir, "fields", 10);
  EXPECT_EQ(resumed->steps_written(), 2u);
  write_step(*resumed, 20, 2.0);

  const std::string xml = read_text(dir + "/fields.xdmf");
  std::string problem;
  EXPECT_TRUE(tags_balanced(xml, problem)) << problem;
  for (const char* group : {"step_000000", "step_000010", "step_000020"}) {
    EXPECT_NE(xml.find(std::string("<Grid Name=\"") + group), std::string::npos) << group;
  }
  H5Reader h5(dir + "/fields.h5");
  ASSERT_TRUE(h5.ok());
  EXPECT_EQ(h5.read<double>("/step_000020/volume", H5T_NATIVE_DOUBLE), std::vector<double>(2, 2.0));
  const std::regex ref(R"(fields\.h5:(/[^<]+)<)");
  int references = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), ref); it != std::sregex_iterator();
       ++it, ++references)
    EXPECT_TRUE(h5.exists((*it)[1])) << (*it)[1];
  // Per step: positions, volume, velocity, material, and 6 tensor columns.
  EXPECT_EQ(references, 3 * (1 + 1 + 1 + 1 + 6));
}

TEST(FieldWriter, MisuseIsReported) {
  FieldWriter writer(output_dir("misuse"));
  EXPECT_THROW(writer.add_scalar("a", {}), std::logic_error);
  EXPECT_THROW(writer.end_step(), std::logic_error);
  writer.begin_step(1, 0.0, std::vector<Vec3>(2, Vec3::Zero()));
  EXPECT_THROW(writer.begin_step(2, 0.0, std::vector<Vec3>{}), std::logic_error);
  EXPECT_THROW(writer.add_scalar("a", {1.0}), std::invalid_argument);
  EXPECT_THROW(writer.add_scalar("a/b", {1.0, 2.0}), std::invalid_argument);
  writer.add_scalar("a", {1.0, 2.0});
  EXPECT_THROW(writer.add_int("a", {1, 2}), std::invalid_argument);
  writer.end_step();
  EXPECT_THROW(writer.begin_step(1, 0.0, std::vector<Vec3>{}), std::runtime_error);
}

TEST(FieldWriter, AFailedResumeLeavesTheEarlierFileWhole) {
  const std::string dir = output_dir("failed_resume");
  const std::vector<Vec3> pos = {{0, 0, 0}, {1, 0, 0}};
  {
    FieldWriter first(dir, "fields");
    for (long step : {0L, 10L, 20L}) {
      first.begin_step(step, 1e-3 * step, pos);
      first.add_scalar("volume", {1.0, 1.0});
      first.end_step();
    }
  }
  // Where the kept steps are copied to cannot be written (as on a full disk): twice.
  std::filesystem::create_directories(dir + "/fields.h5.resume_tmp");
  EXPECT_ANY_THROW(FieldWriter::resume(dir, "fields", 10));
  EXPECT_ANY_THROW(FieldWriter::resume(dir, "fields", 10));
  H5Reader h5(dir + "/fields.h5");
  ASSERT_TRUE(h5.ok());
  for (const char* step : {"/step_000000/volume", "/step_000010/volume", "/step_000020/volume"})
    EXPECT_TRUE(h5.exists(step)) << step;
  std::filesystem::remove_all(dir + "/fields.h5.resume_tmp");
  EXPECT_EQ(FieldWriter::resume(dir, "fields", 10)->steps_written(), 2u);
}

}  // namespace
}  // namespace mpm_lig::io
