#pragma once

#include <string>

namespace mpm_lig::io {

//! Checksums of every file in a folder, as `sha256sum` writes them ("<hex>  <relative path>",
//! one line each, sorted): a user can check a checkpoint with `sha256sum -c MANIFEST`.

//! The SHA-256 of `file` in hexadecimal; throws naming the file when it cannot be read.
std::string sha256_of_file(const std::string& file);

//! Write `folder/manifest_name` listing every regular file under `folder` (recursively, the
//! manifest itself excepted); written to a temporary name and renamed, checked.
void write_manifest(const std::string& folder, const std::string& manifest_name);

//! What is wrong with `folder` against its manifest (a missing manifest, a file missing, added
//! or changed), or "" when every file matches.
std::string manifest_problem(const std::string& folder, const std::string& manifest_name);

}  // namespace mpm_lig::io
