#pragma once

#include <string>

namespace mpm_lig::dem {

//! What is wrong with `file` as a restart file written by engine `engine` ("liggghts" or
//! "lammps") holding `atoms` atoms, or "" when it looks whole. Checked before an engine reads
//! a restart (LIGGGHTS loops forever on an empty file and aborts with a double free on a
//! damaged one, both without a message) and after one writes it (on a full disk it leaves a
//! truncated file and reports nothing).
//!
//! LIGGGHTS: the header must open with the VERSION record ("Version LIGGGHTS..."), and the
//! file must end in the per-process chunks of atom records (an int count of doubles, then
//! records that each start with their own length) holding exactly `atoms` atoms. LAMMPS:
//! the magic string must open and close the file.
std::string restart_file_problem(const std::string& file, const std::string& engine, long atoms);

}  // namespace mpm_lig::dem
