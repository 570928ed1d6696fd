#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace mpm_lig::io {

//! Files replaced as a whole: the new content is written to a temporary beside the target
//! (same folder, so the rename stays on one file system), checked, then renamed over it. A
//! reader, or a run killed at any moment, sees the old file or the new one, never half of one.
//! Every "write, then rename" of the program goes through here (see docs/DESIGN.md §
//! Persistence).

//! The temporary a replace of `target` writes first: `target + suffix`.
std::string temporary_beside(const std::string& target, const std::string& suffix = ".tmp");

//! Rename `temporary` over `target`; a std::runtime_error naming both when it fails.
void rename_over(const std::string& temporary, const std::string& target);

//! Replace `target` with what `write` puts into the file it is given (the temporary beside
//! `target`). When `write` throws or the rename fails, the temporary is removed (unless it is
//! a folder) and `target` is left as it was; the error names the file.
void replace_atomically(const std::string& target,
                        const std::function<void(const std::string& temporary)>& write,
                        const std::string& suffix = ".tmp");

//! Same, for content written to a stream, which is flushed and closed checked (a full disk is
//! an error naming the temporary).
void replace_file(const std::string& target, const std::function<void(std::ostream&)>& write,
                  const std::string& suffix = ".tmp");

//! Same, for a text.
void replace_file(const std::string& target, const std::string& text,
                  const std::string& suffix = ".tmp");

}  // namespace mpm_lig::io
