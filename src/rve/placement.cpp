#include "rve/placement.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "io/checked_stream.h"

namespace mpm_lig::rve {
namespace {

// Layout: the magic line, the grain count (int64), then all positions (3 doubles per grain, by
// grain id), then all image flags (1 int32 per grain), in the machine's byte order (a
// checkpoint is resumed on the machine family that wrote it).
constexpr char kMagic[] = "mpm_lig placement 1\n";
constexpr std::size_t kMagicSize = sizeof kMagic - 1;

std::uintmax_t expected_size(long grains) {
  return kMagicSize + sizeof(std::int64_t) +
         static_cast<std::uintmax_t>(grains) * (3 * sizeof(double) + sizeof(std::int32_t));
}

std::string size_problem(const std::string& file, long grains) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error)
    return "cannot read the size of '" + file + "': " + error.message();
  if (size != expected_size(grains))
    return "'" + file + "' has " + std::to_string(size) + " bytes, not the " +
           std::to_string(expected_size(grains)) + " of " + std::to_string(grains) + " grains";
  return {};
}

}  // namespace

Placement take_placement(dem::Engine& engine) {
  return {engine.gather_atoms("x", 3), engine.gather_atom_ints("image", 1)};
}

void put_placement(dem::Engine& engine, const Placement& placement) {
  engine.scatter_atoms("x", 3, placement.x);
  engine.scatter_atom_ints("image", 1, placement.image);
}

void write_placement(const Placement& placement, const std::string& file, MPI_Comm comm) {
  static_assert(sizeof(int) == sizeof(std::int32_t), "image flags are stored as int32");
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string failure;
  if (rank == 0) {
    try {
      std::ofstream out(file, std::ios::binary | std::ios::trunc);
      const auto grains = static_cast<std::int64_t>(placement.image.size());
      out.write(kMagic, kMagicSize);
      out.write(reinterpret_cast<const char*>(&grains), sizeof grains);
      out.write(reinterpret_cast<const char*>(placement.x.data()),
                static_cast<std::streamsize>(placement.x.size() * sizeof(double)));
      out.write(reinterpret_cast<const char*>(placement.image.data()),
                static_cast<std::streamsize>(placement.image.size() * sizeof(std::int32_t)));
      io::close_checked(out, file);
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }
  // Rank 0's failure ends the write on every rank of the RVE alike.
  int failed = failure.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (failed)
    throw std::runtime_error(rank == 0 ? failure
                                       : "the grain placement '" + file +
                                             "' could not be written (rank 0 of the RVE says why)");
  const std::string problem = size_problem(file, static_cast<long>(placement.image.size()));
  if (!problem.empty())
    throw std::runtime_error("the grain placement just written: " + problem);
}

Placement read_placement(const std::string& file, long grains) {
  const std::string problem = size_problem(file, grains);
  if (!problem.empty())
    throw std::runtime_error("grain placement: " + problem);
  std::ifstream in(file, std::ios::binary);
  char magic[kMagicSize];
  std::int64_t count = 0;
  in.read(magic, kMagicSize);
  in.read(reinterpret_cast<char*>(&count), sizeof count);
  if (!in || std::memcmp(magic, kMagic, kMagicSize) != 0 || count != grains)
    throw std::runtime_error("grain placement: '" + file + "' is not a placement of " +
                             std::to_string(grains) + " grains");
  Placement p;
  p.x.resize(static_cast<std::size_t>(grains) * 3);
  p.image.resize(static_cast<std::size_t>(grains));
  in.read(reinterpret_cast<char*>(p.x.data()),
          static_cast<std::streamsize>(p.x.size() * sizeof(double)));
  in.read(reinterpret_cast<char*>(p.image.data()),
          static_cast<std::streamsize>(p.image.size() * sizeof(std::int32_t)));
  if (!in)
    throw std::runtime_error("grain placement: cannot read '" + file + "'");
  return p;
}

}  // namespace mpm_lig::rve
