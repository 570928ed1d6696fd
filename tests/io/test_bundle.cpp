// Bundles (io/bundle.h): members written and read back bit for bit by their byte ranges, their
// digests those of sha256sum (known vectors) and exact through the packed index; a changed,
// cut or lengthened bundle and a damaged index are refused, naming the bundle.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_files.h"

#include "io/bundle.h"

namespace mpm_lig::io {
namespace {

namespace fs = std::filesystem;

std::string fresh_dir(const std::string& name) {
  return test_support::fresh_dir("bundle", name);
}

using test_support::error_of;

//! Three members of rank 3's bundle in `dir`: text, empty, binary with NULs.
std::vector<BundleMember> write_three(const std::string& dir, std::string* whole) {
  BundleWriter out(dir + "/" + bundle_name(3), 3);
  std::vector<BundleMember> members;
  members.push_back(out.append("abc"));
  members.push_back(out.append(""));
  members.push_back(out.append(std::string("\0\1\2\xff", 4)));
  *whole = out.close();
  return members;
}

TEST(Bundle, DigestsAreSha256) {
  // FIPS 180-2 test vectors.
  EXPECT_EQ(sha256_of_bytes("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_of_bytes(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Bundle, MembersRoundTrip) {
  const std::string dir = fresh_dir("round_trip");
  std::string whole;
  const std::vector<BundleMember> members = write_three(dir, &whole);
  EXPECT_EQ(bundle_name(3), "rank_3.bundle");
  EXPECT_EQ(members[0].offset, 0u);
  EXPECT_EQ(members[1].offset, 3u);
  EXPECT_EQ(members[2].offset, 3u);
  EXPECT_EQ(members[2].length, 4u);
  EXPECT_EQ(whole, sha256_of_file(dir + "/rank_3.bundle"));
  EXPECT_EQ(whole, sha256_of_bytes(read_bytes(dir + "/rank_3.bundle")));
  EXPECT_EQ(read_member(dir, members[0]), "abc");
  EXPECT_EQ(read_member(dir, members[1]), "");
  EXPECT_EQ(read_member(dir, members[2]), std::string("\0\1\2\xff", 4));
  EXPECT_EQ(bundle_layout_problem(dir, members), "");
  // Through the packed index: every field back, the digest exact.
  std::vector<double> row;
  for (const BundleMember& m : members)
    pack(m, row);
  ASSERT_EQ(row.size(), 3 * kBundleMemberWidth);
  for (std::size_t k = 0; k < members.size(); ++k) {
    const BundleMember back = unpack_member(row.data() + k * kBundleMemberWidth);
    EXPECT_EQ(back.rank, 3);
    EXPECT_EQ(back.offset, members[k].offset);
    EXPECT_EQ(back.length, members[k].length);
    EXPECT_EQ(back.sha256, members[k].sha256);
  }
}

TEST(Bundle, ChangesAreRefused) {
  const std::string dir = fresh_dir("changes");
  std::string whole;
  std::vector<BundleMember> members = write_three(dir, &whole);
  const std::string file = dir + "/rank_3.bundle";
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(1);
    f.put('X');
  }
  EXPECT_NE(error_of([&] {
              read_member(dir, members[0]);
            }).find("bytes 0-3 of '" + file + "' have changed since they were written"),
            std::string::npos);
  EXPECT_EQ(read_member(dir, members[2]), std::string("\0\1\2\xff", 4));
  {
    std::ofstream f(file, std::ios::app | std::ios::binary);
    f << 'z';
  }
  EXPECT_NE(
      bundle_layout_problem(dir, members).find("'rank_3.bundle' holds 8 bytes, its members 7"),
      std::string::npos);
  fs::resize_file(file, 5);
  EXPECT_NE(error_of([&] { read_member(dir, members[2]); }).find("it is shorter"),
            std::string::npos);
  EXPECT_NE(bundle_layout_problem(dir, members).find("holds 5 bytes"), std::string::npos);
  members[2].offset = 4;
  EXPECT_NE(bundle_layout_problem(dir, members).find("gap or overlap at byte 3"),
            std::string::npos);
  members[2].offset = 3;
  fs::remove(file);
  EXPECT_NE(error_of([&] { read_member(dir, members[0]); }).find("cannot open '" + file + "'"),
            std::string::npos);
  EXPECT_NE(bundle_layout_problem(dir, members).find("'rank_3.bundle' is missing"),
            std::string::npos);
}

TEST(Bundle, DamagedIndexIsRefused) {
  std::vector<double> row;
  pack(BundleMember{1, 10, 20, sha256_of_bytes("x")}, row);
  for (const double bad : {-1.0, 0.5, 1e300, 4294967296.0}) {
    std::vector<double> damaged = row;
    damaged[3] = bad;
    EXPECT_EQ(error_of([&] { unpack_member(damaged.data()); }), "the bundle index is damaged")
        << bad;
  }
}

}  // namespace
}  // namespace mpm_lig::io
