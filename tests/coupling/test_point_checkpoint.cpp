// The named checkpoint fields of a DEM point: a round trip through the named arrays gives
// back every field, and a checkpoint with other fields or another point count is refused.
#include <map>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "coupling/point_checkpoint.h"

namespace mpm_lig::coupling {
namespace {

//! Named arrays in memory, as a checkpoint file keeps them.
class Store final : public materials::CheckpointWriter, public materials::CheckpointReader {
 public:
  std::string folder() const override { return "/nowhere"; }
  void write(const std::string& name, const std::vector<double>& values) override {
    arrays[name] = values;
  }
  void set(const std::string& name, double value) override { scalars[name] = value; }
  void record_digest(const std::string&, const std::string&) override {}
  bool has(const std::string& name) const override { return arrays.count(name) > 0; }
  std::vector<double> read(const std::string& name) const override { return arrays.at(name); }
  double get(const std::string& name) const override { return scalars.at(name); }
  std::string describe() const override { return "checkpoint 'test'"; }
  std::map<std::string, std::vector<double>> arrays;
  std::map<std::string, double> scalars;
};

PointCheckpoint sample(double seed) {
  PointCheckpoint p;
  for (int k = 0; k < 9; ++k) {
    p.stress.data()[k] = seed + k;
    p.rve.rotation.data()[k] = seed * 10 + k;
    p.rve.streaming.data()[k] = seed * 100 + k;
  }
  p.substeps = seed * 7;
  p.rve.particle_steps = seed * 1e6;
  p.rve.last_mean_stress = -seed * 1e5;
  for (int k = 0; k < DemWork::kValues; ++k)
    p.work[k] = seed * 1e3 + k;
  for (int k = 0; k < QuietPoints::kValues; ++k)
    p.quiet[k] = seed * 1e4 - k;
  for (int k = 0; k < SteadyFlow::kValues; ++k)
    p.flow[k] = seed * 1e5 + 3 * k;
  return p;
}

std::string refusal(const Store& store, std::size_t points) {
  try {
    read_points(store, points);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// A checkpoint of a build before the quiet points' yielding flag (33 values a point) resumes:
// its values in place, the flag not yielding.
TEST(PointCheckpoint, QuietRowsOfTheEarlierWidthReadWithTheNewValueZero) {
  std::vector<double> rows;
  pack(sample(1.5), rows);
  pack(sample(-2.25), rows);
  Store store;
  write_points(store, rows);
  std::vector<double>& quiet = store.arrays.at("quiet_points");
  ASSERT_EQ(quiet.size(), 2u * QuietPoints::kValues);
  std::vector<double> older;
  for (int p = 0; p < 2; ++p)
    older.insert(older.end(), quiet.begin() + p * QuietPoints::kValues,
                 quiet.begin() + p * QuietPoints::kValues + 33);
  quiet = older;
  const std::vector<double> back = read_points(store, 2);
  for (int p = 0; p < 2; ++p) {
    const PointCheckpoint want = sample(p == 0 ? 1.5 : -2.25);
    const PointCheckpoint got = unpack(back.data() + p * point_checkpoint_width());
    for (int k = 0; k < 33; ++k)
      EXPECT_EQ(got.quiet[k], want.quiet[k]) << p << " " << k;
    EXPECT_EQ(got.quiet[33], 0.0);
    EXPECT_EQ(got.flow[0], want.flow[0]);
  }
  quiet.resize(2u * 32);  // neither width: refused
  EXPECT_NE(refusal(store, 2).find("holds"), std::string::npos) << refusal(store, 2);
}

TEST(PointCheckpoint, NamedArraysRoundTripEveryField) {
  std::vector<double> rows;
  pack(sample(1.5), rows);
  pack(sample(-2.25), rows);
  ASSERT_EQ(rows.size(), 2 * point_checkpoint_width());
  Store store;
  write_points(store, rows);
  EXPECT_EQ(store.arrays.at("rotation").size(), 18u);
  EXPECT_EQ(store.arrays.at("rotation")[9], -22.5);
  const std::vector<double> back = read_points(store, 2);
  for (int p = 0; p < 2; ++p) {
    const PointCheckpoint want = sample(p == 0 ? 1.5 : -2.25);
    const PointCheckpoint got = unpack(back.data() + p * point_checkpoint_width());
    EXPECT_EQ(got.stress, want.stress);
    EXPECT_EQ(got.substeps, want.substeps);
    EXPECT_EQ(got.rve.rotation, want.rve.rotation);
    EXPECT_EQ(got.rve.streaming, want.rve.streaming);
    EXPECT_EQ(got.rve.particle_steps, want.rve.particle_steps);
    EXPECT_EQ(got.rve.last_mean_stress, want.rve.last_mean_stress);
    for (int k = 0; k < DemWork::kValues; ++k)
      EXPECT_EQ(got.work[k], want.work[k]);
    for (int k = 0; k < QuietPoints::kValues; ++k)
      EXPECT_EQ(got.quiet[k], want.quiet[k]);
    for (int k = 0; k < SteadyFlow::kValues; ++k)
      EXPECT_EQ(got.flow[k], want.flow[k]);
  }
}

TEST(PointCheckpoint, OtherLayoutsAreRefusedByName) {
  std::vector<double> rows;
  pack(sample(1.0), rows);
  Store good;
  write_points(good, rows);

  Store missing = good;
  missing.arrays.erase("streaming");
  EXPECT_NE(refusal(missing, 1).find("no field 'streaming'"), std::string::npos)
      << refusal(missing, 1);

  Store more = good;
  more.arrays["point_fields"] = {99.0};  // more fields than this version knows
  EXPECT_NE(refusal(more, 1).find("fields do not match"), std::string::npos) << refusal(more, 1);

  Store old_rows;  // the unnamed rows of earlier versions
  old_rows.arrays["rows"] = rows;
  EXPECT_NE(refusal(old_rows, 1).find("names no fields"), std::string::npos)
      << refusal(old_rows, 1);

  EXPECT_NE(refusal(good, 3).find("holds 1 DEM points, the case has 3"), std::string::npos)
      << refusal(good, 3);
}

}  // namespace
}  // namespace mpm_lig::coupling
