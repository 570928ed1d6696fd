// Restart files are checked before an engine reads them and after it writes them: a whole file
// passes; empty, truncated (as a full disk leaves them) and random files are refused with a
// reason, and Rve::from_restart throws instead of hanging (LIGGGHTS loops forever on an empty
// file) or aborting (double free on random bytes).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "core/case_node.h"
#include "dem/restart_check.h"
#include "rve/rve.h"

using namespace mpm_lig;

namespace {

constexpr long kGrains = 60;

rve::RveSpec make_spec(const std::string& engine) {
  const std::string json = R"({"rve": {"engine": ")" + engine + R"(", "dimension": 2, "grains": )" +
                           std::to_string(kGrains) + R"(,
      "radius": {"min": 0.003, "max": 0.007}, "density": 2650, "seed": 5,
      "contact": {"youngs_modulus": 7e8, "poisson_ratio": 0.3, "friction": 0.5,
                  "damping_ratio": 0.1},
      "time_step_fraction": 0.15, "preparation": {"confining_pressure": 1e5},
      "substeps": {"fixed": 10}}})";
  const auto doc = CaseDocument::parse(json);
  return rve::parse_rve_spec(doc.root().child("rve"));
}

std::vector<char> bytes_of(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string write_bytes(const std::string& name, const std::vector<char>& bytes) {
  const std::string file = std::string(MPM_LIG_BINARY_DIR) + "/test_restart_check_" + name;
  std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<long>(bytes.size()));
  return file;
}

class RestartCheck : public ::testing::TestWithParam<std::string> {
 protected:
  //! A packing written by the engine (after a few steps, so that contacts have history).
  std::string whole_file() {
    const rve::RveSpec spec = make_spec(GetParam());
    auto rve = rve::Rve::generate(spec, MPI_COMM_SELF, "packing");
    rve->relax(20);
    const std::string file =
        std::string(MPM_LIG_BINARY_DIR) + "/test_restart_check_" + GetParam() + ".restart";
    rve->write_restart(file);
    return file;
  }
};

TEST_P(RestartCheck, WholeFilesPassDamagedOnesAreRefusedWithAReason) {
  const std::string engine = GetParam();
  const std::string file = whole_file();
  EXPECT_EQ(dem::restart_file_problem(file, engine, kGrains), "");
  const std::vector<char> whole = bytes_of(file);
  ASSERT_GT(whole.size(), 4096u);

  EXPECT_NE(dem::restart_file_problem(write_bytes("empty", {}), engine, kGrains).find("empty"),
            std::string::npos);
  // Cut where a full disk leaves them (whole pages) and one byte short.
  for (const std::size_t size : {std::size_t{4096}, whole.size() - 1}) {
    const std::string cut = write_bytes(
        "cut", std::vector<char>(whole.begin(), whole.begin() + static_cast<long>(size)));
    EXPECT_NE(dem::restart_file_problem(cut, engine, kGrains).find("incomplete"), std::string::npos)
        << size << " bytes: " << dem::restart_file_problem(cut, engine, kGrains);
  }
  std::mt19937 random(7);
  std::vector<char> noise(whole.size());
  for (char& c : noise)
    c = static_cast<char>(random() & 0xff);
  EXPECT_NE(dem::restart_file_problem(write_bytes("noise", noise), engine, kGrains).find("not a"),
            std::string::npos);
  if (engine == "liggghts") {
    // A file of other grains is not taken for this packing, nor called damaged.
    EXPECT_EQ(
        dem::restart_file_problem(file, engine, kGrains + 1),
        "holds " + std::to_string(kGrains) + " grains, grains says " + std::to_string(kGrains + 1));
  }
}

TEST_P(RestartCheck, AnRveRefusesAnEmptyOrRandomFileInsteadOfHangingOrAborting) {
  const rve::RveSpec spec = make_spec(GetParam());
  std::mt19937 random(11);
  std::vector<char> noise(20000);
  for (char& c : noise)
    c = static_cast<char>(random() & 0xff);
  for (const std::string& file : {write_bytes("empty", {}), write_bytes("noise", noise)}) {
    try {
      rve::Rve::from_restart(spec, file, MPI_COMM_SELF, "clone");
      ADD_FAILURE() << "'" << file << "' was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("clone: restart file '" + file + "'"), std::string::npos)
          << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, RestartCheck, ::testing::Values("liggghts", "lammps"));

}  // namespace
