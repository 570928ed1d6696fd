#pragma once

#include <string>

namespace mpm_lig::dem {

//! Why `name` cannot be given to a DEM engine as a file name, or "" when it can.
//!
//! The engines parse file names like any other word of their input (docs/DESIGN.md §3.8, "LIGGGHTS
//! input parsing applies to file names"): unquoted, a space splits the name, `$` starts a
//! variable and `#` a comment. Inside double quotes all three are plain characters, so
//! quoted_file_name() takes them. What no quoting saves: a double quote, a line break or other
//! control byte, and `*` and `%`, which `write_restart`/`read_restart` replace by the time step
//! and the processor number.
std::string unusable_file_name(const std::string& name);

//! `name` in double quotes, one word of an engine command. Throws std::invalid_argument for a
//! name unusable_file_name() refuses (callers check first, where the name comes from).
std::string quoted_file_name(const std::string& name);

}  // namespace mpm_lig::dem
