#include "dem/fd_capture.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>

namespace mpm_lig::dem::detail {
namespace {
FdCapture* g_active = nullptr;  // engine calls are not re-entrant: one capture at a time
}

FdCapture::FdCapture(bool capture_stdout, bool capture_stderr) {
  memory_fd_ = memfd_create("mpm_lig_engine_output", MFD_CLOEXEC);
  if (memory_fd_ < 0)
    throw std::runtime_error("memfd_create failed");
  std::fflush(stdout);
  std::fflush(stderr);
  std::cout.flush();
  int n = 0;
  for (int fd : {1, 2}) {
    if ((fd == 1 && !capture_stdout) || (fd == 2 && !capture_stderr))
      continue;
    redirects_[n].fd = fd;
    redirects_[n].saved = dup(fd);
    dup2(memory_fd_, fd);
    ++n;
  }
  g_active = this;
}

FdCapture::~FdCapture() {
  restore();
  if (memory_fd_ >= 0)
    close(memory_fd_);
}

void FdCapture::restore() {
  if (g_active == this)
    g_active = nullptr;
  std::fflush(stdout);
  std::fflush(stderr);
  std::cout.flush();
  for (Redirect& r : redirects_) {
    if (r.saved < 0)
      continue;
    dup2(r.saved, r.fd);
    close(r.saved);
    r.saved = -1;
  }
}

std::string FdCapture::finish() {
  restore();
  if (memory_fd_ < 0)
    return {};
  std::string text;
  char buffer[4096];
  lseek(memory_fd_, 0, SEEK_SET);
  for (ssize_t got; (got = read(memory_fd_, buffer, sizeof buffer)) > 0;)
    text.append(buffer, static_cast<std::size_t>(got));
  close(memory_fd_);
  memory_fd_ = -1;
  return text;
}

void FdCapture::restore_active() {
  if (g_active)
    g_active->restore();
}

}  // namespace mpm_lig::dem::detail
