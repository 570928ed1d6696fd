#include "io/checked_stream.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace mpm_lig::io {
namespace {

[[noreturn]] void fail(const std::string& filename) {
  const int error = errno;
  throw std::runtime_error("cannot write '" + filename + "'" +
                           (error ? std::string(": ") + std::strerror(error) : std::string()));
}

}  // namespace

void flush_checked(std::ofstream& out, const std::string& filename) {
  errno = 0;
  if (!out.flush())
    fail(filename);
}

void close_checked(std::ofstream& out, const std::string& filename) {
  errno = 0;
  out.flush();
  out.close();
  if (!out)
    fail(filename);
}

}  // namespace mpm_lig::io
