#include "io/run_folder.h"

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace mpm_lig::io {
namespace {

namespace fs = std::filesystem;

//! What an earlier run leaves: a new run into the folder would overwrite or orphan them.
constexpr const char* kResults[] = {"summary.json", "history.csv", "results.h5",
                                    "results.xdmf", "snapshots",   "checkpoints/latest"};
//! The files a run keeps in its folder (beside each, its temporaries `NAME.*`) and its folders
//! (whatever is in them is the run's): the names check_run_folder() guards.
constexpr const char* kRunFiles[] = {"summary.json", "history.csv",        "results.h5",
                                     "results.xdmf", RunFolderLock::kFile, "prepared.restart"};
constexpr const char* kRunFolders[] = {"checkpoints", "snapshots", "packings"};
//! What --replace removes: the results and what else a run writes.
constexpr const char* kRunOutputs[] = {"summary.json",    "history.csv", "results.h5",
                                       "results.xdmf",    "snapshots",   "packings",
                                       "prepared.restart"};

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0)
    return "unknown";
  return name;
}

std::string owner_record() {
  const std::time_t now = std::time(nullptr);
  char when[32] = {};
  std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  std::ostringstream out;
  out << host_name() << ' ' << getpid() << ' ' << when << '\n';
  return out.str();
}

//! "pid P on host H since T" from a record written by owner_record(), or "" when unreadable.
std::string describe_record(const std::string& record, std::string& host, long& pid) {
  std::istringstream in(record);
  std::string when;
  if (!(in >> host >> pid) || pid <= 0)
    return "";
  std::getline(in, when);
  return "pid " + std::to_string(pid) + " on host " + host + " since" + when;
}

std::string read_record(int fd) {
  char buffer[512] = {};
  const ssize_t n = pread(fd, buffer, sizeof(buffer) - 1, 0);
  return n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : "";
}

void write_record(int fd, const std::string& file) {
  const std::string record = owner_record();
  if (ftruncate(fd, 0) != 0 ||
      pwrite(fd, record.data(), record.size(), 0) != static_cast<ssize_t>(record.size()))
    throw RunFolderRefused("cannot write the lock file '" + file + "': " + std::strerror(errno));
}

bool same_file(int fd, const std::string& file) {
  struct stat open_one {
  }, named_one{};
  return fstat(fd, &open_one) == 0 && lstat(file.c_str(), &named_one) == 0 &&
         open_one.st_dev == named_one.st_dev && open_one.st_ino == named_one.st_ino;
}

std::string busy_message(const std::string& dir, const std::string& holder) {
  return "the output folder '" + dir + "' is in use by another mpm_lig run (" +
         (holder.empty() ? std::string("holder unknown") : holder) +
         "): one run at a time writes a folder; wait for it to end, or choose another --output";
}

//! A file system without record locks: the owner record decides (not atomic; said in
//! docs/running.md).
void take_by_record(int fd, const std::string& dir, const std::string& file) {
  std::string host;
  long pid = 0;
  const std::string holder = describe_record(read_record(fd), host, pid);
  if (!holder.empty() && pid != getpid()) {
    if (host != host_name())
      throw RunFolderRefused(busy_message(dir, holder) +
                             " (this file system has no locks: if "
                             "no run uses the folder, remove '" +
                             file + "')");
    if (kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM)
      throw RunFolderRefused(busy_message(dir, holder));
  }
  write_record(fd, file);
}

//! What a name of `type` is, for a message.
const char* kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::regular:
      return "a file";
    case fs::file_type::directory:
      return "a folder";
    case fs::file_type::symlink:
      return "a symbolic link";
    case fs::file_type::fifo:
      return "a pipe";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device";
    default:
      return "of an unknown kind";
  }
}

//! The refusal of `path`, of `type`, where the run keeps `kept`.
RunFolderRefused misplaced(const fs::path& path, fs::file_type type, const std::string& kept) {
  return RunFolderRefused("'" + path.string() + "' is " + kind_of(type) + " where mpm_lig keeps " +
                          kept +
                          ": a run reads, writes and removes only files and folders in its "
                          "output folder (nothing was changed; move it away or choose another "
                          "--output)");
}

//! Whatever is in the run's folder `folder`, at any depth, is a file or a folder (links are
//! listed, not followed).
void check_inside(const fs::path& folder) {
  for (fs::recursive_directory_iterator it(folder), end; it != end; ++it) {
    const fs::file_type type = it->symlink_status().type();
    if (type != fs::file_type::regular && type != fs::file_type::directory)
      throw misplaced(it->path(), type, "only files and folders");
  }
}

}  // namespace

RunFolderLock::RunFolderLock(const std::string& dir) : file_((fs::path(dir) / kFile).string()) {
  std::error_code missing;
  const fs::file_type type = fs::symlink_status(file_, missing).type();
  if (type != fs::file_type::not_found && type != fs::file_type::regular)
    throw misplaced(file_, type, "a file");
  // A release unlinks the file: one opened just before that is no longer the folder's lock,
  // so the lock taken is checked to be on the file the name still names.
  for (int attempt = 0; attempt < 10; ++attempt) {
    fd_ = open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0)
      throw RunFolderRefused("cannot create the lock file '" + file_ +
                             "': " + std::strerror(errno));
    struct flock lock {};
    lock.l_type = F_WRLCK;
    lock.l_whence = SEEK_SET;
    if (fcntl(fd_, F_SETLK, &lock) == 0) {
      if (same_file(fd_, file_)) {
        write_record(fd_, file_);
        return;
      }
    } else if (errno == EACCES || errno == EAGAIN) {
      std::string host;
      long pid = 0;
      const std::string holder = describe_record(read_record(fd_), host, pid);
      close(fd_);
      fd_ = -1;
      throw RunFolderRefused(busy_message(dir, holder));
    } else if (errno == ENOLCK || errno == EOPNOTSUPP || errno == ENOSYS || errno == EINVAL) {
      take_by_record(fd_, dir, file_);
      return;
    } else {
      const int error = errno;
      close(fd_);
      fd_ = -1;
      throw RunFolderRefused("cannot lock '" + file_ + "': " + std::strerror(error));
    }
    close(fd_);
    fd_ = -1;
  }
  throw RunFolderRefused(busy_message(dir, "its lock file changes hands continuously"));
}

RunFolderLock::~RunFolderLock() {
  if (fd_ < 0)
    return;
  // Unlinked while still locked, so that no other run takes a file about to disappear.
  unlink(file_.c_str());
  close(fd_);
}

void check_run_folder(const std::string& dir) {
  std::error_code missing;
  if (!fs::is_directory(dir, missing))
    return;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    const fs::file_type type = e.symlink_status().type();
    for (const char* file : kRunFiles) {
      const bool temporary = name.rfind(std::string(file) + ".", 0) == 0;
      // A temporary that is a folder is left for its write to fail: nothing goes through it.
      const bool fits =
          type == fs::file_type::regular || (temporary && type == fs::file_type::directory);
      if ((name == file || temporary) && !fits)
        throw misplaced(e.path(), type, "a file");
    }
    for (const char* folder : kRunFolders) {
      if (name == folder && type != fs::file_type::directory)
        throw misplaced(e.path(), type, "a folder");
      if (name == folder)
        check_inside(e.path());
    }
  }
}

std::string earlier_results(const std::string& dir) {
  std::error_code ignored;
  for (const char* name : kResults) {
    if (fs::exists(fs::path(dir) / name, ignored))
      return name;
  }
  return "";
}

void remove_run_outputs(const std::string& dir) {
  for (const char* name : kRunOutputs)
    fs::remove_all(fs::path(dir) / name);
  // Of checkpoints/ only what a run writes there.
  const fs::path root = fs::path(dir) / "checkpoints";
  if (!fs::is_directory(fs::symlink_status(root)))
    return;
  for (const fs::directory_entry& e : fs::directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    if (name == "latest" || name == "latest.tmp" || name.rfind("step_", 0) == 0)
      fs::remove_all(e.path());
  }
  if (fs::is_empty(root))
    fs::remove(root);
}

}  // namespace mpm_lig::io
