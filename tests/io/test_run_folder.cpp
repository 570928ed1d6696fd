#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "test_files.h"

#include "io/run_folder.h"

namespace mpm_lig::io {
namespace {

namespace fs = std::filesystem;

using test_support::error_of;

std::string fresh_dir(const std::string& name) {
  return test_support::fresh_dir("run_folder", name);
}

void write_text(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

//! A run folder as a run leaves it: results, a checkpoint, packings and snapshots.
std::string run_folder(const std::string& name) {
  const fs::path dir = fresh_dir(name);
  for (const char* file :
       {"summary.json", "history.csv", "results.h5", "results.xdmf", "checkpoints/latest",
        "checkpoints/step_4/mpm.h5", "checkpoints/step_4/m0/rank_0.bundle",
        "packings/packing_0.restart", "snapshots/point_000001/rve_000004.vtk"})
    write_text(dir / file, "ours\n");
  return dir.string();
}

//! The message check_run_folder(dir) refuses with ("" when it accepts the folder).
std::string refusal(const std::string& dir) {
  return error_of([&] { check_run_folder(dir); });
}

TEST(RunFolder, AcceptsItsOwnFilesAndFoldersAndWhatElseTheUserKeeps) {
  const std::string dir = run_folder("accepted");
  fs::create_symlink("/etc/hostname", dir + "/notes.txt");  // not a name a run uses
  fs::create_directories(dir + "/results.h5.resume_tmp");   // a write into it fails instead
  EXPECT_EQ(refusal(dir), "");
  EXPECT_EQ(refusal(dir + "/no_such_folder"), "");  // a new run creates it
  const std::string link = fresh_dir("link_to_folder") + "/out";
  fs::create_directory_symlink(dir, link);  // the folder on the command line may be a link
  EXPECT_EQ(refusal(link), "");
}

TEST(RunFolder, RefusesALinkAtEveryNameARunUsesNamingIt) {
  const std::string other = run_folder("other_run");
  for (const char* name :
       {"summary.json", "history.csv", "results.h5", "results.xdmf", "mpm_lig.lock",
        "prepared.restart", "summary.json.partial", "history.csv.resume_tmp", "checkpoints",
        "checkpoints/latest", "checkpoints/step_4", "checkpoints/step_4/m0/rank_0.bundle",
        "packings", "packings/migration", "snapshots", "snapshots/point_000001"}) {
    for (const bool dangling : {false, true}) {
      const std::string dir = run_folder("link");
      const fs::path at = fs::path(dir) / name;
      fs::remove_all(at);
      fs::create_symlink(dangling ? other + "/missing" : other + "/" + name, at);
      const std::string error = refusal(dir);
      EXPECT_NE(error.find("'" + at.string() + "' is a symbolic link"), std::string::npos)
          << name << ": " << error;
      EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
  }
}

TEST(RunFolder, RefusesSpecialFilesAndFilesAndFoldersInEachOthersPlace) {
  const auto refused = [](const std::string& name, const std::string& what,
                          void (*make)(const fs::path&)) {
    const std::string dir = run_folder("kinds");
    const fs::path at = fs::path(dir) / name;
    fs::remove_all(at);
    make(at);
    const std::string error = refusal(dir);
    EXPECT_NE(error.find("'" + at.string() + "' is " + what), std::string::npos)
        << name << ": " << error;
  };
  const auto pipe = [](const fs::path& at) { ASSERT_EQ(::mkfifo(at.c_str(), 0600), 0); };
  const auto folder = [](const fs::path& at) { fs::create_directories(at); };
  const auto file = [](const fs::path& at) { write_text(at, "x"); };
  refused("history.csv", "a pipe", pipe);
  refused("results.xdmf.tmp", "a pipe", pipe);
  refused("checkpoints/step_4/mpm.h5", "a pipe", pipe);
  refused("results.h5", "a folder where mpm_lig keeps a file", folder);
  refused("mpm_lig.lock", "a folder where mpm_lig keeps a file", folder);
  refused("checkpoints", "a file where mpm_lig keeps a folder", file);
  refused("packings", "a file where mpm_lig keeps a folder", file);
}

TEST(RunFolder, TheLockNeverFollowsALink) {
  const std::string dir = fresh_dir("lock");
  const std::string victim = fresh_dir("lock_victim") + "/data";
  write_text(victim, "kept\n");
  fs::create_symlink(victim, dir + "/" + RunFolderLock::kFile);
  EXPECT_THROW(RunFolderLock lock(dir), RunFolderRefused);
  EXPECT_EQ(read_text(victim), "kept\n");
  EXPECT_TRUE(fs::is_symlink(dir + "/" + RunFolderLock::kFile));
}

TEST(RunFolder, ReplaceNeverRemovesThroughALink) {
  const std::string other = run_folder("replace_other");
  const std::string dir = run_folder("replace");
  fs::remove_all(dir + "/checkpoints");
  fs::create_directory_symlink(other + "/checkpoints", dir + "/checkpoints");
  fs::remove_all(dir + "/snapshots");
  fs::create_directory_symlink(other + "/snapshots", dir + "/snapshots");
  remove_run_outputs(dir);
  EXPECT_EQ(read_text(other + "/checkpoints/latest"), "ours\n");
  EXPECT_TRUE(fs::exists(other + "/checkpoints/step_4/mpm.h5"));
  EXPECT_TRUE(fs::exists(other + "/snapshots/point_000001/rve_000004.vtk"));
  EXPECT_FALSE(fs::exists(dir + "/history.csv"));
}

}  // namespace
}  // namespace mpm_lig::io
