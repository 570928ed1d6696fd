#pragma once

#include <stdexcept>
#include <string>

namespace mpm_lig {

//! A problem in the case file. `path()` names the JSON location, e.g. `rve.radius.min`.
//! The application prints it as "<file>: <path>: <message>" and exits with code 2.
class CaseError : public std::runtime_error {
 public:
  CaseError(std::string path, const std::string& message)
      : std::runtime_error(path + ": " + message), path_(std::move(path)) {}

  //! The JSON path of the offending value.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

//! A checkpoint `--resume` cannot continue from (damaged, written for another case, ...):
//! bad input like a bad case, refused before any result file is touched (exit 2).
class ResumeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! A run failure that every rank finds alike, at the same point of the same step, because it
//! comes from state replicated on all ranks (the MPM's): the job then ends in order (each rank
//! returns exit code 1, rank 0 prints the message), without MPI_Abort and the launcher's
//! noise after it.
class ReplicatedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Exit code for a case that fails validation (bad input).
inline constexpr int kExitBadCase = 2;

}  // namespace mpm_lig
