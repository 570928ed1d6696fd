#pragma once

#include <string>

namespace mpm_lig::dem::detail {

//! Redirects the process's stdout and/or stderr (file descriptors 1 and 2) into memory for
//! its lifetime and hands back what was written. For engine calls that print where no screen
//! setting reaches (LIGGGHTS: `printf` at read_restart, `std::cerr` style warnings).
class FdCapture {
 public:
  FdCapture(bool capture_stdout, bool capture_stderr);
  ~FdCapture();
  FdCapture(const FdCapture&) = delete;
  FdCapture& operator=(const FdCapture&) = delete;

  //! Restore the descriptors and return what was captured (once; later calls return "").
  std::string finish();

  //! Restore the descriptors of the capture in progress, if any, without reading it: for
  //! the fatal-error path, which must print to the real stderr.
  static void restore_active();

 private:
  struct Redirect {
    int fd = -1;     // 1 or 2
    int saved = -1;  // dup of the original
  };
  void restore();

  int memory_fd_ = -1;
  Redirect redirects_[2];
};

}  // namespace mpm_lig::dem::detail
