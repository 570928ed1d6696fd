#pragma once

#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "io/file_digest.h"

namespace mpm_lig::io {

//! Bundles: many small files of one rank as byte ranges ("members") of one file,
//! `rank_<r>.bundle`, appended in order. The index of the members (rank, offset, length and
//! the SHA-256 the writing rank computed) is kept elsewhere (a checkpoint's mpm.h5), so a
//! reader on any rank reads one member with one pread and checks it without reading the rest.
//! docs/hpc.md §3.

//! One member: bytes [offset, offset + length) of the bundle of rank `rank`.
struct BundleMember {
  int rank = 0;
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
  std::string sha256;  //!< hexadecimal, 64 characters
};

//! Doubles per member when packed: rank, offset, length and the digest as eight 32-bit words
//! (every value exact in a double, and finite).
constexpr std::size_t kBundleMemberWidth = 11;
void pack(const BundleMember& member, std::vector<double>& row);
//! The member packed at `row`; throws when the row is not a member.
BundleMember unpack_member(const double* row);

//! "rank_<r>.bundle".
std::string bundle_name(int rank);

//! Appends members to a new bundle `file` (created, or truncated), hashing as it writes.
class BundleWriter {
 public:
  BundleWriter(const std::string& file, int rank);
  //! Append `bytes`; the member it became.
  BundleMember append(const std::string& bytes);
  //! Flush and close, checked; the SHA-256 of the whole bundle.
  std::string close();
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  int rank_ = 0;
  std::ofstream out_;
  std::uint64_t size_ = 0;
  Sha256 whole_;
};

//! The whole content of `file`; throws naming it.
std::string read_bytes(const std::string& file);
//! Write `bytes` to `file` (replaced), checked.
void write_bytes(const std::string& file, const std::string& bytes);

//! The bytes of `member` from `folder/bundle_name(member.rank)` (one pread), checked against
//! its SHA-256; throws naming the bundle and the byte range when it cannot be read or has
//! changed since it was written.
std::string read_member(const std::string& folder, const BundleMember& member);

//! What is wrong with the bundles in `folder` against `members` (all members of all bundles):
//! a bundle's size is not the end of its last member or its members leave gaps or overlap,
//! so that every byte of a bundle belongs to exactly one checked member; "" when none.
std::string bundle_layout_problem(const std::string& folder,
                                  const std::vector<BundleMember>& members);

}  // namespace mpm_lig::io
