#include "core/resources.h"

#include <sys/resource.h>
#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <fstream>

#include "core/case_error.h"

namespace mpm_lig {
namespace {

//! The cgroup v2 (or v1) memory limit of this process, or 0 when there is none.
double control_group_limit() {
  for (const char* file :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(file);
    double limit = 0.0;
    if (in >> limit && limit > 0.0)
      return limit;  // "max" (no limit) does not read as a number
  }
  return 0.0;
}

//! Ranks of `comm` on the machine with the most of them.
int ranks_per_machine(MPI_Comm comm) {
  MPI_Comm local = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
  int here = 1, most = 1;
  MPI_Comm_size(local, &here);
  MPI_Comm_free(&local);
  MPI_Allreduce(&here, &most, 1, MPI_INT, MPI_MAX, comm);
  return most;
}

}  // namespace

double machine_memory_bytes() {
  const double physical =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double limit = control_group_limit();
  return limit > 0.0 ? std::min(physical, limit) : physical;
}

std::string describe_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 6) {
    bytes /= 1000.0;
    ++u;
  }
  char text[64];
  std::snprintf(text, sizeof text, bytes < 10.0 ? "%.1f %s" : "%.3g %s", bytes, units[u]);
  return text;
}

void MemoryBudget::add(const std::string& path, double bytes, const std::string& what,
                       bool spread) {
  parts_.push_back({path, bytes, what, spread});
}

double MemoryBudget::total() const {
  double sum = 0.0;
  for (const Part& p : parts_)
    sum += p.bytes;
  return sum;
}

void MemoryBudget::check(MPI_Comm comm) const {
  const int sharing = ranks_per_machine(comm);
  // A limit on this process's address space (ulimit -v) bounds each rank on its own.
  struct rlimit limit {};
  const double own = getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY
                         ? static_cast<double>(limit.rlim_cur)
                         : 0.0;
  const double here =
      own > 0.0 ? std::min(machine_memory_bytes(), own * sharing) : machine_memory_bytes();
  // The smallest machine decides, on every rank alike: a refusal on some ranks only would
  // leave the others waiting in the run's first collective call.
  double available = here;
  MPI_Allreduce(&here, &available, 1, MPI_DOUBLE, MPI_MIN, comm);
  if (parts_.empty() || total() * sharing <= available)
    return;
  const auto largest = std::max_element(
      parts_.begin(), parts_.end(), [](const Part& a, const Part& b) { return a.bytes < b.bytes; });
  std::string parts;
  for (const Part& p : parts_)
    parts += (parts.empty() ? "" : "; ") + p.path + ": " + p.what + ", " + describe_bytes(p.bytes);
  throw CaseError(largest->path,
                  "the run would need about " + describe_bytes(total()) + " of memory per rank (" +
                      parts + ") and " + std::to_string(sharing) + " rank(s) share a machine of " +
                      describe_bytes(available) + ": make the case smaller" +
                      (largest->spread ? ", or run it on more machines (its RVEs spread out)"
                                       : " (the MPM is copied on every rank)"));
}

}  // namespace mpm_lig
