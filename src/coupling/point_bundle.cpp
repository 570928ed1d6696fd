#include "coupling/point_bundle.h"

#include <filesystem>
#include <stdexcept>

namespace mpm_lig::coupling {
namespace {

constexpr const char* kMemberNames[kPointMembers] = {"engine restart", "grain placement"};

bool is_leader(MPI_Comm group) {
  int rank = 0;
  MPI_Comm_rank(group, &rank);
  return rank == 0;
}

std::string scratch_file(const std::string& scratch) {
  return scratch + "/point.restart";
}

//! The member files of the point at the scratch file `file`, in member order.
std::string member_file(const std::string& file, std::size_t member) {
  return member == 0 ? file : rve::Rve::placement_file(file);
}

//! The scratch files go once copied: a file truncated and written again makes ext4 write it
//! out at close (auto_da_alloc), which tripled a checkpoint's time; a new file does not.
void remove_members(const std::string& file, bool leader) {
  for (std::size_t m = 0; leader && m < kPointMembers; ++m)
    std::filesystem::remove(member_file(file, m));
}

}  // namespace

PointBundleWriter::PointBundleWriter(const std::string& folder, const std::string& scratch,
                                     int rank, MPI_Comm group)
    : scratch_(scratch), leader_(is_leader(group)), group_(group) {
  if (leader_) {
    std::filesystem::create_directories(scratch_);
    bundle_ = std::make_unique<io::BundleWriter>(folder + "/" + io::bundle_name(rank), rank);
  }
  MPI_Barrier(group_);
}

PointBundleWriter::~PointBundleWriter() = default;

void PointBundleWriter::add(rve::Rve& rve, std::vector<double>& index) {
  const std::string file = scratch_file(scratch_);
  rve.write_checkpoint(file);
  // Every rank of the group has checked the files before the next point overwrites them.
  MPI_Barrier(group_);
  for (std::size_t m = 0; m < kPointMembers; ++m) {
    if (leader_)
      io::pack(bundle_->append(io::read_bytes(member_file(file, m))), index);
    else
      index.insert(index.end(), io::kBundleMemberWidth, 0.0);
  }
  remove_members(file, leader_);
}

std::string PointBundleWriter::close() {
  if (!leader_)
    return "";
  const std::string digest = bundle_->close();
  std::filesystem::remove_all(scratch_);
  return digest;
}

std::string unbundle_point(const std::string& folder, const double* index,
                           const std::string& scratch, MPI_Comm group) {
  const std::string file = scratch_file(scratch);
  // The previous point's files are read by every rank of the group before they are replaced.
  MPI_Barrier(group);
  if (is_leader(group)) {
    std::filesystem::create_directories(scratch);
    remove_members(file, true);
    for (std::size_t m = 0; m < kPointMembers; ++m) {
      const io::BundleMember member = io::unpack_member(index + m * io::kBundleMemberWidth);
      try {
        io::write_bytes(member_file(file, m), io::read_member(folder, member));
      } catch (const std::exception& e) {
        throw std::runtime_error(std::string("its ") + kMemberNames[m] + ": " + e.what());
      }
    }
  }
  MPI_Barrier(group);
  return file;
}

void remove_scratch(const std::string& scratch, MPI_Comm group) {
  MPI_Barrier(group);
  if (is_leader(group))
    std::filesystem::remove_all(scratch);
}

}  // namespace mpm_lig::coupling
