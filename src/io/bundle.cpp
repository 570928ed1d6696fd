#include "io/bundle.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include "io/checked_stream.h"

namespace mpm_lig::io {
namespace {

std::string range_of(const std::string& bundle, const BundleMember& m) {
  return "bytes " + std::to_string(m.offset) + "-" + std::to_string(m.offset + m.length) + " of '" +
         bundle + "'";
}

}  // namespace

void pack(const BundleMember& member, std::vector<double>& row) {
  row.push_back(static_cast<double>(member.rank));
  row.push_back(static_cast<double>(member.offset));
  row.push_back(static_cast<double>(member.length));
  for (std::size_t w = 0; w < 8; ++w)
    row.push_back(static_cast<double>(std::stoul(member.sha256.substr(8 * w, 8), nullptr, 16)));
}

BundleMember unpack_member(const double* row) {
  const auto whole = [](double v) {
    return v >= 0.0 && v < 9.0e15 && v == static_cast<double>(static_cast<std::uint64_t>(v));
  };
  for (std::size_t k = 0; k < kBundleMemberWidth; ++k) {
    if (!whole(row[k]) || (k >= 3 && row[k] > 4294967295.0))
      throw std::runtime_error("the bundle index is damaged");
  }
  BundleMember m;
  m.rank = static_cast<int>(row[0]);
  m.offset = static_cast<std::uint64_t>(row[1]);
  m.length = static_cast<std::uint64_t>(row[2]);
  static const char* const kHex = "0123456789abcdef";
  for (std::size_t w = 0; w < 8; ++w) {
    const auto word = static_cast<std::uint32_t>(row[3 + w]);
    for (int shift = 28; shift >= 0; shift -= 4)
      m.sha256 += kHex[(word >> shift) & 15u];
  }
  return m;
}

std::string bundle_name(int rank) {
  return "rank_" + std::to_string(rank) + ".bundle";
}

BundleWriter::BundleWriter(const std::string& file, int rank)
    : file_(file), rank_(rank), out_(file, std::ios::binary | std::ios::trunc) {
  if (!out_)
    throw std::runtime_error("cannot create '" + file + "'");
}

BundleMember BundleWriter::append(const std::string& bytes) {
  out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out_)
    throw std::runtime_error("cannot write '" + file_ + "'");
  whole_.add(bytes.data(), bytes.size());
  BundleMember m{rank_, size_, bytes.size(), sha256_of_bytes(bytes)};
  size_ += bytes.size();
  return m;
}

std::string BundleWriter::close() {
  close_checked(out_, file_);
  return whole_.hex();
}

std::string read_bytes(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes;
  if (in) {
    in.seekg(0, std::ios::end);
    bytes.resize(static_cast<std::size_t>(in.tellg()));
    in.seekg(0);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  if (!in)
    throw std::runtime_error("cannot read '" + file + "'");
  return bytes;
}

void write_bytes(const std::string& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  close_checked(out, file);
}

std::string read_member(const std::string& folder, const BundleMember& member) {
  const std::string bundle = folder + "/" + bundle_name(member.rank);
  const int fd = ::open(bundle.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error("cannot open '" + bundle + "': " + std::strerror(errno));
  std::string bytes(member.length, '\0');
  std::size_t done = 0;
  int error = 0;
  while (done < bytes.size()) {
    const ssize_t got = ::pread(fd, bytes.data() + done, bytes.size() - done,
                                static_cast<off_t>(member.offset + done));
    if (got < 0 && errno == EINTR)
      continue;
    if (got <= 0) {
      error = got < 0 ? errno : 0;
      break;
    }
    done += static_cast<std::size_t>(got);
  }
  ::close(fd);
  if (done < bytes.size())
    throw std::runtime_error(
        "cannot read " + range_of(bundle, member) +
        (error ? std::string(": ") + std::strerror(error) : ": it is shorter"));
  if (sha256_of_bytes(bytes) != member.sha256)
    throw std::runtime_error(range_of(bundle, member) +
                             " have changed since they were written (checksum mismatch)");
  return bytes;
}

std::string bundle_layout_problem(const std::string& folder,
                                  const std::vector<BundleMember>& members) {
  std::map<int, std::vector<const BundleMember*>> by_rank;
  for (const BundleMember& m : members)
    by_rank[m.rank].push_back(&m);
  for (auto& [rank, list] : by_rank) {
    std::sort(list.begin(), list.end(),
              [](const BundleMember* a, const BundleMember* b) { return a->offset < b->offset; });
    std::uint64_t end = 0;
    for (const BundleMember* m : list) {
      if (m->offset != end)
        return "the members of '" + bundle_name(rank) + "' leave a gap or overlap at byte " +
               std::to_string(end);
      end += m->length;
    }
    const std::string bundle = folder + "/" + bundle_name(rank);
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(bundle, error);
    if (error)
      return "'" + bundle_name(rank) + "' is missing";
    if (size != end)
      return "'" + bundle_name(rank) + "' holds " + std::to_string(size) + " bytes, its members " +
             std::to_string(end) + " (cut or added to since it was written)";
  }
  return "";
}

}  // namespace mpm_lig::io
