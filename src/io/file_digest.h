#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>

namespace mpm_lig::io {

//! SHA-256 of bytes given piece by piece (OpenSSL's).
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void add(const char* bytes, std::size_t size);
  //! The digest of everything added, in hexadecimal; call once.
  std::string hex();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

//! The SHA-256 of `bytes` in hexadecimal.
std::string sha256_of_bytes(const std::string& bytes);

//! Checksums of every file in a folder, as `sha256sum` writes them ("<hex>  <relative path>",
//! one line each, sorted): a user can check a checkpoint with `sha256sum -c MANIFEST`.

//! The SHA-256 of `file` in hexadecimal; throws naming the file when it cannot be read.
std::string sha256_of_file(const std::string& file);

//! Write `folder/manifest_name` listing every regular file under `folder` (recursively, the
//! manifest itself excepted); written to a temporary name and renamed, checked. A file in
//! `known` (relative path -> checksum, computed by whoever wrote it) is listed with that
//! checksum instead of being read again.
void write_manifest(const std::string& folder, const std::string& manifest_name,
                    const std::map<std::string, std::string>& known = {});

//! What is wrong with `folder` against its manifest (a missing manifest, a file missing, added
//! or changed), or "" when every file matches. Files for which `present_only` is true are
//! checked for presence only (their content is checked otherwise, e.g. per bundle member).
std::string manifest_problem(const std::string& folder, const std::string& manifest_name,
                             bool (*present_only)(const std::string& relative) = nullptr);

}  // namespace mpm_lig::io
