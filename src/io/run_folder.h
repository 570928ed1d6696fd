#pragma once

#include <stdexcept>
#include <string>

namespace mpm_lig::io {

//! A run folder another writer holds, or that holds results a new run would overwrite: the
//! run is refused (exit 2) before it touches anything.
class RunFolderRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! One writer per run folder, for the life of the run: `mpm_lig.lock` in the folder, locked
//! with a POSIX record lock (fcntl), which NFS (lockd) and Lustre/GPFS (mounted with flock)
//! honour across nodes and which the kernel releases when the process ends in any way
//! (exit, exception, MPI_Abort, SIGKILL): a lock file left by a dead run is found unlocked
//! and taken over. On a file system without record locks the file's owner record (host, pid)
//! decides: a live process on this host keeps it, a dead one's is taken over, another host's
//! is refused with the advice to remove the file. Held by one process (MPI rank 0).
class RunFolderLock {
 public:
  //! Takes `dir` (an existing folder) for this process; throws RunFolderRefused naming the
  //! holder when another process has it, or when the lock file is not a regular file (a
  //! link there is never followed).
  explicit RunFolderLock(const std::string& dir);
  ~RunFolderLock();
  RunFolderLock(const RunFolderLock&) = delete;
  RunFolderLock& operator=(const RunFolderLock&) = delete;

  static constexpr const char* kFile = "mpm_lig.lock";

 private:
  std::string file_;
  int fd_ = -1;
};

//! Refuses (RunFolderRefused naming the path, nothing changed) a run folder `dir` in which a
//! name the run reads, writes or removes could lead out of it: a symbolic link, pipe, socket
//! or device at the name of one of its files (summary.json, history.csv, results.h5,
//! results.xdmf, mpm_lig.lock, prepared.restart) or of a temporary of one (`NAME.*`), or at
//! any depth in one of its folders (checkpoints/, snapshots/, packings/); a folder where it
//! keeps a file, a file where it keeps a folder. `dir` itself may be a link to a folder (the
//! user's choice on the command line); a missing `dir` is accepted (a new run creates it).
void check_run_folder(const std::string& dir);

//! The results of an earlier run that `dir` holds (the first found of summary.json,
//! history.csv, results.h5, results.xdmf, snapshots/, checkpoints/latest), or "" when none.
std::string earlier_results(const std::string& dir);

//! Removes from `dir` what a run writes there (results, fields, history, summary, snapshots,
//! checkpoints, prepared packings with the cost record beside them) and nothing else; a
//! symbolic link among them is removed itself, never what it points to.
void remove_run_outputs(const std::string& dir);

}  // namespace mpm_lig::io
