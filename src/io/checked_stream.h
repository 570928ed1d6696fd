#pragma once

#include <fstream>
#include <string>

namespace mpm_lig::io {

//! Flush `out`; a std::runtime_error naming `filename` and the system's reason when what was
//! written did not reach the file (a full disk, a quota, a folder removed under the run).
void flush_checked(std::ofstream& out, const std::string& filename);

//! Flush and close `out`, with the same error (some file systems report only at close).
void close_checked(std::ofstream& out, const std::string& filename);

}  // namespace mpm_lig::io
