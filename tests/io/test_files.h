#pragma once

// Helpers of the io tests: a fresh folder under the build tree, and the message of a throw.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace mpm_lig::io::test_support {

//! An empty folder `test_output/<suite>/<name>` in the build tree.
inline std::string fresh_dir(const std::string& suite, const std::string& name) {
  const std::string dir = std::string(MPM_LIG_BINARY_DIR) + "/test_output/" + suite + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

//! The message of what `work` throws, or "" when it does not throw.
template <class Work>
std::string error_of(Work&& work) {
  try {
    work();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace mpm_lig::io::test_support
