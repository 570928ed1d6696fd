#include "io/file_digest.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <openssl/evp.h>

#include "io/atomic_file.h"

namespace mpm_lig::io {
namespace {

namespace fs = std::filesystem;

//! Relative path -> checksum of every regular file under `folder` but `skip`; the checksum
//! of a file is taken from `known` when it is there, and is "" when `unread` says so.
std::map<std::string, std::string> digests(const fs::path& folder, const std::string& skip,
                                           const std::map<std::string, std::string>& known,
                                           bool (*unread)(const std::string&)) {
  std::map<std::string, std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file())
      continue;
    const std::string relative = fs::relative(entry.path(), folder).generic_string();
    if (relative == skip)
      continue;
    const auto given = known.find(relative);
    if (given != known.end())
      out[relative] = given->second;
    else
      out[relative] = unread && unread(relative) ? "" : sha256_of_file(entry.path().string());
  }
  return out;
}

}  // namespace

struct Sha256::Context {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> evp{EVP_MD_CTX_new(), &EVP_MD_CTX_free};
};

Sha256::Sha256() : context_(std::make_unique<Context>()) {
  if (!context_->evp || EVP_DigestInit_ex(context_->evp.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256 is not available");
}

Sha256::~Sha256() = default;

void Sha256::add(const char* bytes, std::size_t size) {
  if (size > 0)
    EVP_DigestUpdate(context_->evp.get(), bytes, size);
}

std::string Sha256::hex() {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(context_->evp.get(), digest, &length);
  static const char* const kHex = "0123456789abcdef";
  std::string hex;
  for (unsigned int k = 0; k < length; ++k) {
    hex += kHex[digest[k] >> 4];
    hex += kHex[digest[k] & 15];
  }
  return hex;
}

std::string sha256_of_bytes(const std::string& bytes) {
  Sha256 sha;
  sha.add(bytes.data(), bytes.size());
  return sha.hex();
}

std::string sha256_of_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw std::runtime_error("cannot read '" + file + "'");
  Sha256 sha;
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    if (in.gcount() > 0)
      sha.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad())
    throw std::runtime_error("cannot read '" + file + "'");
  return sha.hex();
}

void write_manifest(const std::string& folder, const std::string& manifest_name,
                    const std::map<std::string, std::string>& known) {
  const fs::path target = fs::path(folder) / manifest_name;
  const auto listed = digests(folder, manifest_name, known, nullptr);
  replace_file(target.string(), [&](std::ostream& out) {
    for (const auto& [file, digest] : listed)
      out << digest << "  " << file << '\n';
  });
}

std::string manifest_problem(const std::string& folder, const std::string& manifest_name,
                             bool (*present_only)(const std::string& relative)) {
  std::ifstream in(fs::path(folder) / manifest_name);
  if (!in)
    return "it has no " + manifest_name + " (incomplete, or written before checksums)";
  std::map<std::string, std::string> listed;
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t gap = line.find("  ");
    if (gap != 64 || line.size() <= gap + 2)
      return manifest_name + " is damaged";
    listed[line.substr(gap + 2)] = line.substr(0, gap);
  }
  const auto present = digests(folder, manifest_name, {}, present_only);
  for (const auto& [file, digest] : listed) {
    const auto found = present.find(file);
    if (found == present.end())
      return "'" + file + "' is missing";
    if (!found->second.empty() && found->second != digest)
      return "'" + file + "' has changed since it was written (checksum mismatch)";
  }
  for (const auto& [file, digest] : present) {
    if (listed.count(file) == 0)
      return "'" + file + "' was added after it was written";
  }
  return "";
}

}  // namespace mpm_lig::io
