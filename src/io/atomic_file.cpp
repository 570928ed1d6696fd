#include "io/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "io/checked_stream.h"

namespace mpm_lig::io {

std::string temporary_beside(const std::string& target, const std::string& suffix) {
  return target + suffix;
}

void rename_over(const std::string& temporary, const std::string& target) {
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error)
    throw std::runtime_error("cannot rename '" + temporary + "' to '" + target +
                             "': " + error.message());
}

void replace_atomically(const std::string& target,
                        const std::function<void(const std::string& temporary)>& write,
                        const std::string& suffix) {
  const std::string temporary = temporary_beside(target, suffix);
  try {
    write(temporary);
    rename_over(temporary, target);
  } catch (...) {
    std::error_code ignored;
    if (!std::filesystem::is_directory(temporary, ignored))
      std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void replace_file(const std::string& target, const std::function<void(std::ostream&)>& write,
                  const std::string& suffix) {
  replace_atomically(
      target,
      [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::trunc);
        if (!out)
          throw std::runtime_error("cannot write '" + temporary + "'");
        write(out);
        close_checked(out, temporary);
      },
      suffix);
}

void replace_file(const std::string& target, const std::string& text, const std::string& suffix) {
  replace_file(
      target, [&](std::ostream& out) { out << text; }, suffix);
}

}  // namespace mpm_lig::io
