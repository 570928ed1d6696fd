#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/case_node.h"

using mpm_lig::CaseDocument;
using mpm_lig::CaseError;

namespace {

//! The path named by the CaseError that `f` throws ("" if it throws none).
template <class F>
std::string error_path(F&& f) {
  try {
    f();
  } catch (const CaseError& e) {
    return e.path();
  }
  return "";
}

const char* kCase = R"({
  "title": "t",
  "rve": {"grains": 400, "radius": {"min": 0.003, "max": 0.007}, "seed": 4.0},
  "materials": [{"type": "a", "E": 1e6}, {"type": "b", "E": -1}],
  "_comment": "ignored"
})";

}  // namespace

TEST(CaseNode, ReadsTypedValuesAndAcceptsIntegralFloats) {
  const auto doc = CaseDocument::parse(kCase);
  const auto rve = doc.root().child("rve");
  EXPECT_EQ(rve.get<int>("grains"), 400);
  EXPECT_EQ(rve.get<long>("seed"), 4);
  EXPECT_DOUBLE_EQ(rve.child("radius").positive("max"), 0.007);
  EXPECT_EQ(rve.get_or<std::string>("engine", "liggghts"), "liggghts");
}

TEST(CaseNode, ErrorsNameTheFullJsonPath) {
  const auto doc = CaseDocument::parse(kCase);
  const auto root = doc.root();
  EXPECT_EQ(error_path([&] { root.child("rve").get<std::string>("grains"); }), "rve.grains");
  EXPECT_EQ(error_path([&] { root.child("rve").child("radius").get<double>("mean"); }),
            "rve.radius.mean");
  EXPECT_EQ(error_path([&] { root.children("materials")[1].positive("E"); }), "materials[1].E");
  EXPECT_EQ(error_path([&] { root.child("title"); }), "title");
  EXPECT_EQ(error_path([&] { root.choice("title", {"a", "b"}); }), "title");
  EXPECT_EQ(error_path([&] { root.child("rve").in_range("grains", 0, 100); }), "rve.grains");
}

TEST(CaseNode, RejectsNonIntegralCounts) {
  const auto doc = CaseDocument::parse(R"({"n": 4.5, "flag": 1})");
  EXPECT_EQ(error_path([&] { doc.root().get<int>("n"); }), "n");
  EXPECT_EQ(error_path([&] { doc.root().get<bool>("flag"); }), "flag");
}

TEST(CaseDocument, ReportsKeysNobodyRead) {
  const auto doc = CaseDocument::parse(kCase);
  const auto root = doc.root();
  root.get<std::string>("title");
  const auto rve = root.child("rve");
  rve.get<int>("grains");
  rve.get<long>("seed");
  rve.child("radius").get<double>("min");
  for (const auto& m : root.children("materials")) {
    m.get<std::string>("type");
    m.get<double>("E");
  }
  EXPECT_EQ(error_path([&] { doc.check_all_used(); }), "rve.radius.max");
  rve.child("radius").get<double>("max");
  EXPECT_EQ(error_path([&] { doc.check_all_used(); }), "");
}

TEST(CaseDocument, SyntaxErrorIsACaseError) {
  EXPECT_EQ(error_path([] { CaseDocument::parse("{\"a\": }"); }), "(file)");
  EXPECT_EQ(error_path([] { CaseDocument::load("/nonexistent/case.json"); }), "(file)");
}

TEST(CaseNode, FilePathsAreRelativeToTheCaseFile) {
  const std::string dir = ::testing::TempDir() + "/case_dir";
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/c.json";
  std::ofstream(file) << R"({"a": "packing.restart", "b": "/abs/p.restart", "c": ""})";
  const auto doc = CaseDocument::load(file);
  EXPECT_EQ(doc.root().file_path("a"),
            std::filesystem::path(dir + "/packing.restart").lexically_normal().string());
  EXPECT_EQ(doc.root().file_path("b"), "/abs/p.restart");
  EXPECT_EQ(error_path([&] { doc.root().file_path("c"); }), "c");
  // Parsed text has no folder: names stay as given.
  EXPECT_EQ(CaseDocument::parse(R"({"a": "x/y"})").root().file_path("a"), "x/y");
}
