#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "test_files.h"

#include "io/atomic_file.h"

namespace mpm_lig::io {
namespace {

namespace fs = std::filesystem;

std::string fresh_dir(const std::string& name) {
  return test_support::fresh_dir("atomic_file", name);
}

std::string read_text(const std::string& filename) {
  std::ifstream in(filename);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

using test_support::error_of;

TEST(AtomicFile, ReplacesTheWholeFileAndLeavesNoTemporary) {
  const std::string dir = fresh_dir("replace");
  const std::string target = dir + "/a.txt";
  replace_file(target, "first\n");
  replace_file(target, [](std::ostream& out) { out << "second " << 2 << '\n'; });
  EXPECT_EQ(read_text(target), "second 2\n");
  EXPECT_FALSE(fs::exists(temporary_beside(target)));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, AFailedWriteLeavesTheTargetAsItWasAndRemovesTheTemporary) {
  const std::string dir = fresh_dir("failed_write");
  const std::string target = dir + "/a.txt";
  replace_file(target, "kept\n");
  const std::string error = error_of([&] {
    replace_file(target, [](std::ostream& out) {
      out << "half";
      throw std::runtime_error("stopped while writing");
    });
  });
  EXPECT_EQ(error, "stopped while writing");
  EXPECT_EQ(read_text(target), "kept\n");
  EXPECT_FALSE(fs::exists(temporary_beside(target)));
}

TEST(AtomicFile, AFullDiskIsAnErrorNamingTheTemporary) {
  if (!fs::exists("/dev/full"))
    GTEST_SKIP() << "no /dev/full";
  const std::string dir = fresh_dir("full_disk");
  const std::string target = dir + "/summary.json";
  replace_file(target, "kept\n");
  const std::string temporary = temporary_beside(target, ".partial");
  fs::create_symlink("/dev/full", temporary);
  const std::string error = error_of([&] { replace_file(target, "lost\n", ".partial"); });
  EXPECT_NE(error.find("cannot write '" + temporary + "'"), std::string::npos) << error;
  EXPECT_EQ(read_text(target), "kept\n");
}

TEST(AtomicFile, AFailedRenameNamesBothFilesAndKeepsAFolderInTheWay) {
  const std::string dir = fresh_dir("failed_rename");
  const std::string target = dir + "/a.txt";
  fs::create_directories(target + "/occupied");  // a non-empty folder cannot be renamed over
  const std::string error = error_of([&] { replace_file(target, "text\n"); });
  EXPECT_NE(error.find("cannot rename '" + temporary_beside(target) + "' to '" + target + "'"),
            std::string::npos)
      << error;
  EXPECT_TRUE(fs::is_directory(target + "/occupied"));
  EXPECT_FALSE(fs::exists(temporary_beside(target)));
  // A temporary that is a folder (someone else's) is left alone.
  const std::string other = dir + "/b.txt";
  fs::create_directories(temporary_beside(other));
  EXPECT_NE(error_of([&] { replace_file(other, "text\n"); }), "");
  EXPECT_TRUE(fs::is_directory(temporary_beside(other)));
  EXPECT_FALSE(fs::exists(other));
}

}  // namespace
}  // namespace mpm_lig::io
