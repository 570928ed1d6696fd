#pragma once

#include <string>
#include <vector>

#include <mpi.h>

namespace mpm_lig {

//! Most steps (MPM steps, DEM steps of one preparation) a case may ask for: far beyond any
//! run that ends (1e12 steps of 1 µs each take 11 days), and exact in a double and a long.
inline constexpr double kMaxSteps = 1e12;

//! Memory of the machine this process runs on [bytes]: its physical memory, or the limit of
//! its control group (a batch job's share) when that is lower.
double machine_memory_bytes();

//! The memory a run will need on each rank, part by part, estimated from the case before
//! anything is built, so that a case too large for the machine is refused at once instead of
//! failing (or being killed) after its output folder exists.
class MemoryBudget {
 public:
  //! `bytes` per rank for the part of the case at JSON `path`; `what` says what it holds;
  //! `spread` when the part is divided among the ranks (DEM RVEs), not copied on each.
  void add(const std::string& path, double bytes, const std::string& what, bool spread = false);
  double total() const;
  //! Collective over `comm`: a CaseError naming the largest part's path unless all ranks of
  //! `comm` that share a machine fit into its memory together (and each rank into its own
  //! address-space limit, `ulimit -v`, if it has one); the smallest machine decides for all.
  void check(MPI_Comm comm) const;

 private:
  struct Part {
    std::string path;
    double bytes;
    std::string what;
    bool spread;
  };
  std::vector<Part> parts_;
};

//! `bytes` for a message: "3.2 GB", "120 MB".
std::string describe_bytes(double bytes);

}  // namespace mpm_lig
