#include "mpm/checkpoint_folder.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/case_error.h"

namespace mpm_lig::mpm {
namespace {

constexpr std::size_t kLatestMaxBytes = 64;

//! The content of `latest` without its line end, or "" when it cannot be read.
std::string read_latest(const std::string& run_dir, bool& present) {
  const std::string file = CheckpointFolder::root(run_dir) + "/latest";
  present = std::filesystem::is_regular_file(file);
  std::ifstream in(file);
  std::string text;
  std::copy_n(
      std::istreambuf_iterator<char>(in),
      std::min<std::uintmax_t>(kLatestMaxBytes + 1, present ? std::filesystem::file_size(file) : 0),
      std::back_inserter(text));
  if (!text.empty() && text.back() == '\n')
    text.pop_back();
  return text;
}

}  // namespace

std::string CheckpointFolder::root(const std::string& run_dir) {
  return run_dir + "/checkpoints";
}

std::string CheckpointFolder::step_name(long step) {
  return "step_" + std::to_string(step);
}

bool CheckpointFolder::is_step_name(const std::string& name) {
  const std::string prefix = "step_";
  constexpr std::size_t kMaxDigits = 18;  // a long
  if (name.size() <= prefix.size() || name.size() > prefix.size() + kMaxDigits ||
      name.compare(0, prefix.size(), prefix) != 0)
    return false;
  return std::all_of(name.begin() + static_cast<long>(prefix.size()), name.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

std::string CheckpointFolder::latest_name_or_empty(const std::string& run_dir) {
  bool present = false;
  const std::string name = read_latest(run_dir, present);
  return is_step_name(name) ? name : "";
}

std::string CheckpointFolder::latest(const std::string& run_dir) {
  bool present = false;
  const std::string name = read_latest(run_dir, present);
  const std::string file = root(run_dir) + "/latest";
  if (!present)
    throw ResumeError("no checkpoint in '" + run_dir + "' (" + file + " is missing)");
  if (!is_step_name(name))
    throw ResumeError("'" + file +
                      "' does not name a checkpoint of this folder (it must hold "
                      "a plain step_<n>); nothing was read or changed");
  const std::string folder = root(run_dir) + "/" + name;
  if (!std::filesystem::is_directory(folder))
    throw ResumeError("'" + file + "' names " + name + ", but '" + folder + "' is missing");
  return folder;
}

}  // namespace mpm_lig::mpm
