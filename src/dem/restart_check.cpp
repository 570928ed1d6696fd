#include "dem/restart_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

namespace mpm_lig::dem {
namespace {

using Bytes = std::vector<char>;

// Restart layouts as LIGGGHTS 3.8 (write_restart.cpp, LAMMPS of 2013) and LAMMPS 2021
// (lmprestart.h) write them; native byte order, int = 4 bytes, double = 8.
constexpr std::int32_t kVersionRecord = 0;
constexpr const char kLiggghtsVersion[] = "Version LIGGGHTS";
constexpr const char kLammpsMagic[] = "LammpS RestartT";  // with its NUL: 16 bytes
constexpr std::size_t kMaxVersionLength = 1024;

template <class T>
T value_at(const Bytes& bytes, std::size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof v);
  return v;
}

//! Atoms in the chunk of `count` doubles that starts at `data`, or -1 if its records do not
//! tile it exactly (each record starts with its own length, a whole number >= 1).
long atoms_in_chunk(const Bytes& bytes, std::size_t data, long count) {
  long k = 0, atoms = 0;
  while (k < count) {
    const double length = value_at<double>(bytes, data + 8 * static_cast<std::size_t>(k));
    if (!(length >= 1.0) || length != std::floor(length) || length > static_cast<double>(count - k))
      return -1;
    k += static_cast<long>(length);
    ++atoms;
  }
  return atoms;
}

//! Whether the bytes in [begin, end) close with chunks holding exactly `atoms` atoms. Chunks
//! are found from the end backwards: a chunk of n doubles ending at `end` starts with the int
//! n at end - 4 - 8 n. A stray match inside the data is possible, hence the search.
bool ends_with_chunks(const Bytes& bytes, std::size_t begin, std::size_t end, long atoms,
                      int depth) {
  if (atoms == 0)
    return true;
  if (depth > 4096 || end < begin + 4)
    return false;
  for (std::size_t count = 0; 4 + 8 * count <= end - begin; ++count) {
    const std::size_t start = end - 4 - 8 * count;
    if (value_at<std::int32_t>(bytes, start) != static_cast<std::int32_t>(count))
      continue;
    const long found = atoms_in_chunk(bytes, start + 4, static_cast<long>(count));
    if (found >= 0 && found <= atoms &&
        ends_with_chunks(bytes, begin, start, atoms - found, depth + 1))
      return true;
  }
  return false;
}

//! The atom count the header declares (its NATOMS record), or -1 when the header cannot be
//! walked up to it. Records: an int flag, then a value whose type the flag fixes (LIGGGHTS
//! 3.8: 0 VERSION, 4 UNITS and 22 ATOM_STYLE strings, 5 NTIMESTEP bigint, the rest int, 23
//! NATOMS bigint).
long declared_atoms(const Bytes& bytes, std::size_t offset) {
  constexpr std::int32_t kNtimestep = 5, kAtomStyle = 22, kNatoms = 23;
  for (std::int32_t expected = 1; offset + 12 <= bytes.size(); ++expected) {
    const std::int32_t flag = value_at<std::int32_t>(bytes, offset);
    if (flag != expected)
      return -1;
    offset += 4;
    if (flag == kNatoms)
      return static_cast<long>(value_at<std::int64_t>(bytes, offset));
    if (flag == 4 || flag == kAtomStyle)
      offset += 4 + static_cast<std::size_t>(std::max(0, value_at<std::int32_t>(bytes, offset)));
    else
      offset += flag == kNtimestep ? 8 : 4;
  }
  return -1;
}

std::string liggghts_problem(const Bytes& bytes, long atoms) {
  if (bytes.size() < 8 || value_at<std::int32_t>(bytes, 0) != kVersionRecord)
    return "not a LIGGGHTS restart file (no version record at its start)";
  const std::int32_t length = value_at<std::int32_t>(bytes, 4);
  if (length < 1 || static_cast<std::size_t>(length) > kMaxVersionLength ||
      bytes.size() < 8 + static_cast<std::size_t>(length) ||
      std::strncmp(bytes.data() + 8, kLiggghtsVersion, sizeof kLiggghtsVersion - 1) != 0 ||
      bytes[7 + static_cast<std::size_t>(length)] != '\0')
    return "not a LIGGGHTS restart file (its version record is not LIGGGHTS')";
  const std::size_t header = 8 + static_cast<std::size_t>(length);
  // A file of another packing is named as such, not taken for a damaged one.
  const long declared = declared_atoms(bytes, header);
  if (atoms > 0 && declared >= 0 && declared != atoms)
    return "holds " + std::to_string(declared) + " grains, grains says " + std::to_string(atoms);
  if (atoms > 0 && !ends_with_chunks(bytes, header, bytes.size(), atoms, 0))
    return "incomplete or damaged: it does not end with the records of " + std::to_string(atoms) +
           " grains (truncated, e.g. written to a full disk?)";
  return "";
}

std::string lammps_problem(const Bytes& bytes) {
  const std::size_t magic = sizeof kLammpsMagic;
  if (bytes.size() < 2 * magic || std::memcmp(bytes.data(), kLammpsMagic, magic) != 0)
    return "not a LAMMPS restart file (no magic string at its start)";
  if (std::memcmp(bytes.data() + bytes.size() - magic, kLammpsMagic, magic) != 0)
    return "incomplete: no magic string at its end (truncated, e.g. written to a full disk?)";
  return "";
}

}  // namespace

std::string restart_file_problem(const std::string& file, const std::string& engine, long atoms) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    return "cannot be read";
  const Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
    return "cannot be read";
  if (bytes.empty())
    return "empty (0 bytes)";
  return engine == "lammps" ? lammps_problem(bytes) : liggghts_problem(bytes, atoms);
}

}  // namespace mpm_lig::dem
