// Case text, messages, engine file names, checked writes and the memory budget: the checks
// that keep malformed input and failing disks from crashing or misleading a run.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/case_node.h"
#include "core/case_text.h"
#include "core/printable.h"
#include "core/resources.h"
#include "dem/file_name.h"
#include "io/csv_history.h"
#include "io/summary.h"

using mpm_lig::CaseDocument;
using mpm_lig::CaseError;

namespace {

//! The CaseError that `f` throws, as "path|message" ("" if it throws none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const CaseError& e) {
    return e.path() + "|" + e.what();
  }
  return "";
}

std::string path_of(const std::string& error) {
  return error.substr(0, error.find('|'));
}

std::string nested_arrays(int depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("mpm_lig_input_checks_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST(CaseText, NumberBeyondADoubleIsNamedByItsPath) {
  const std::string e = error_of([] { CaseDocument::parse(R"({"a": {"b": [1, 1e400]}})"); });
  EXPECT_EQ(path_of(e), "a.b[1]");
  EXPECT_NE(e.find("1e400"), std::string::npos) << e;
  EXPECT_EQ(path_of(error_of([] { CaseDocument::parse(R"({"end": {"time": -1e400}})"); })),
            "end.time");
  // The largest double still reads.
  EXPECT_EQ(error_of([] { CaseDocument::parse(R"({"x": 1.7e308, "y": 4.9e-324})"); }), "");
}

TEST(CaseText, DuplicatedKeysAreRefusedWhereverTheyAre) {
  EXPECT_EQ(path_of(error_of([] { CaseDocument::parse(R"({"a": 1, "a": 2})"); })), "a");
  EXPECT_EQ(path_of(error_of(
                [] { CaseDocument::parse(R"({"m": [{"id": 1}, {"id": 2, "E": 1, "id": 3}]})"); })),
            "m[1].id");
  // The same key in two different objects is fine.
  EXPECT_EQ(error_of([] { CaseDocument::parse(R"({"a": {"x": 1}, "b": {"x": 1}})"); }), "");
}

TEST(CaseText, NestingIsBoundedWithoutRecursion) {
  using mpm_lig::kMaxCaseDepth;
  EXPECT_EQ(
      error_of([] { CaseDocument::parse("{\"t\": " + nested_arrays(kMaxCaseDepth - 1) + "}"); }),
      "");
  const std::string e =
      error_of([] { CaseDocument::parse("{\"t\": " + nested_arrays(200000) + "}"); });
  EXPECT_NE(e.find("nested deeper than"), std::string::npos);
  EXPECT_EQ(path_of(e).rfind("t[0]", 0), 0u);
  EXPECT_LT(e.size(), 1000u);
}

TEST(CaseText, NulBytesAndTrailingGarbageAreRefused) {
  const std::string json = R"({"a": 1})";
  const std::string nul = error_of([&] { CaseDocument::parse(json + std::string(4, '\0')); });
  EXPECT_EQ(path_of(nul), "(file)");
  EXPECT_NE(nul.find("NUL byte at offset 8"), std::string::npos) << nul;
  EXPECT_EQ(path_of(error_of([&] { CaseDocument::parse(json + " x"); })), "(file)");
  EXPECT_EQ(path_of(error_of([] { CaseDocument::parse(""); })), "(file)");
}

TEST(CaseText, InvalidUtf8GivesAPrintableMessageNamingWhere) {
  const std::string e = error_of([] { CaseDocument::parse("{\"title\": \"a\xff\xfe\"}"); });
  EXPECT_EQ(path_of(e), "(file)");
  EXPECT_NE(e.find("in title"), std::string::npos) << e;
  EXPECT_EQ(mpm_lig::printable(e), e) << "the message holds raw bytes";
}

TEST(CaseText, HugeValuesAreDescribedBriefly) {
  std::string many = "1";
  for (int i = 0; i < 100000; ++i)
    many += ",1";
  const std::string huge = "{\"n\": \"" + std::string(1000000, 'x') + "\", \"v\": [" + many + "]}";
  const auto doc = CaseDocument::parse(huge);
  const std::string e1 = error_of([&] { doc.root().get<int>("n"); });
  const std::string e2 = error_of([&] { doc.root().get<bool>("v"); });
  EXPECT_EQ(path_of(e1), "n");
  EXPECT_LT(e1.size(), 200u);
  EXPECT_LT(e2.size(), 200u);
}

TEST(CaseFile, OnlyRegularFilesOfBoundedSizeAreRead) {
  const auto dir = scratch("files");
  EXPECT_NE(error_of([&] { CaseDocument::load(dir.string()); }).find("is a folder"),
            std::string::npos);
  EXPECT_NE(error_of([] { CaseDocument::load("/dev/zero"); }).find("a device"), std::string::npos);
  const auto fifo = dir / "pipe.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Opening a pipe would wait for a writer: this must return at once.
  EXPECT_NE(error_of([&] { CaseDocument::load(fifo.string()); }).find("a pipe"), std::string::npos);
  const auto big = dir / "big.json";
  std::ofstream(big) << std::string(mpm_lig::kMaxCaseFileBytes + 1, ' ') << "{}";
  EXPECT_NE(error_of([&] { CaseDocument::load(big.string()); }).find("bytes"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Printable, KeepsTextEscapesBytesAndBoundsTheLength) {
  using mpm_lig::printable;
  EXPECT_EQ(printable("Hertz–Mindlin, σ = −P\n\tok"), "Hertz–Mindlin, σ = −P\n\tok");
  EXPECT_EQ(printable(std::string("a\x01\x7f") + "\xff" + "\xc3("), "a\\x01\\x7f\\xff\\xc3(");
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a UTF-16 surrogate
  EXPECT_EQ(printable(std::string(10000, 'a'), 100), std::string(100, 'a') + "...");
}

TEST(EngineFileNames, QuotedOrRefused) {
  using mpm_lig::dem::quoted_file_name;
  using mpm_lig::dem::unusable_file_name;
  EXPECT_EQ(quoted_file_name("/a b/$x #y/it's.restart"), "\"/a b/$x #y/it's.restart\"");
  for (const std::string bad : {"a\"b", "run*", "p%q", "a\nb", "a\tb", ""})
    EXPECT_NE(unusable_file_name(bad), "") << bad;
  EXPECT_THROW(quoted_file_name("run*/x"), std::invalid_argument);
}

TEST(CheckedWrites, AFullDiskEndsTheWriteWithAnError) {
  // /dev/full takes the open and refuses every write with ENOSPC, as a full disk does.
  try {
    mpm_lig::io::CsvHistory history("/dev/full", {"a", "b"});
    history.write({1.0, 2.0});
    FAIL() << "a history on a full disk wrote without an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("No space left"), std::string::npos) << e.what();
  }
  const auto dir = scratch("summary");
  std::filesystem::create_symlink("/dev/full", dir / "summary.json.partial");
  EXPECT_THROW(mpm_lig::io::write_json((dir / "summary.json").string(), {{"a", 1}}),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir / "summary.json"));
  std::filesystem::remove_all(dir);
}

TEST(MemoryBudget, RefusesWhatCannotFitNamingTheLargestPart) {
  mpm_lig::MemoryBudget fits;
  fits.add("mesh.cells", 1e6, "grid");
  EXPECT_NO_THROW(fits.check(MPI_COMM_WORLD));
  mpm_lig::MemoryBudget too_big;
  too_big.add("mesh.cells", 1e6, "grid");
  too_big.add("materials[0].rve.grains", 1e18, "RVEs", true);
  const std::string e = error_of([&] { too_big.check(MPI_COMM_WORLD); });
  EXPECT_EQ(path_of(e), "materials[0].rve.grains");
  EXPECT_NE(e.find("1.0 EB"), std::string::npos) << e;
  EXPECT_GT(mpm_lig::machine_memory_bytes(), 1e8);
}
