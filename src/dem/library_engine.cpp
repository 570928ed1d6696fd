#include "dem/library_engine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dem/velocity_field.h"
#include "library.h"  // the engine's own C interface (include path set per module)
#include "lmptype.h"

// Image flags go through the library as C ints (type 0); a build with 64-bit image flags
// (LAMMPS_BIGBIG) would need another transfer type.
static_assert(sizeof(LAMMPS_NS::imageint) == sizeof(int), "image flags are not 32-bit ints");

namespace mpm_lig::dem::detail {

LibraryEngine::LibraryEngine(MPI_Comm comm, const EngineOptions& options)
    : comm_(comm), options_(options) {}

LibraryEngine::~LibraryEngine() {
  // The engine fcloses its screen (our stream) here; OutputRing copes with that.
  if (handle_)
    lammps_close(handle_);
}

std::vector<std::string> LibraryEngine::engine_args(const std::string& program) const {
  return {program, "-screen", "none", "-log",
          options_.log_file.empty() ? "none" : options_.log_file};
}

void LibraryEngine::adopt(void* handle, FILE** engine_screen) {
  handle_ = handle;
  *engine_screen = output_.stream();
}

void LibraryEngine::command(const std::string& line) {
  if (line.compare(0, 4, "run ") == 0)
    ++runs_;
  lammps_command(handle_, const_cast<char*>(line.c_str()));
}

void LibraryEngine::commands(const std::string& script) {
  for (const std::string& line : split_script(script))
    command(line);
}

void LibraryEngine::add_velocity_field(const Mat3& gradient, const Vec3& origin, int dimension) {
  commands(velocity_field_commands(gradient, origin, dimension, "mpm_stream"));
}

double LibraryEngine::compute_scalar(const std::string& compute_id) {
  auto* value = static_cast<double*>(
      lammps_extract_compute(handle_, const_cast<char*>(compute_id.c_str()), 0, 0));
  if (!value)
    throw std::runtime_error("engine has no global scalar compute '" + compute_id + "'");
  return *value;
}

std::vector<double> LibraryEngine::compute_vector(const std::string& compute_id, int length) {
  auto* values = static_cast<double*>(
      lammps_extract_compute(handle_, const_cast<char*>(compute_id.c_str()), 0, 1));
  if (!values)
    throw std::runtime_error("engine has no global vector compute '" + compute_id + "'");
  return std::vector<double>(values, values + length);
}

std::vector<double> LibraryEngine::gather_atoms(const std::string& name, int count) {
  std::vector<double> data(static_cast<std::size_t>(atom_count()) * count);
  lammps_gather_atoms(handle_, const_cast<char*>(name.c_str()), 1, count, data.data());
  return data;
}

void LibraryEngine::scatter_atoms(const std::string& name, int count,
                                  const std::vector<double>& values) {
  check_atom_values(values.size(), count, name);
  // The library reads the values only; its signature (LAMMPS 2021) is not const.
  lammps_scatter_atoms(handle_, const_cast<char*>(name.c_str()), 1, count,
                       const_cast<double*>(values.data()));
}

std::vector<int> LibraryEngine::gather_atom_ints(const std::string& name, int count) {
  std::vector<int> data(static_cast<std::size_t>(atom_count()) * count);
  lammps_gather_atoms(handle_, const_cast<char*>(name.c_str()), 0, count, data.data());
  return data;
}

void LibraryEngine::scatter_atom_ints(const std::string& name, int count,
                                      const std::vector<int>& values) {
  check_atom_values(values.size(), count, name);
  lammps_scatter_atoms(handle_, const_cast<char*>(name.c_str()), 0, count,
                       const_cast<int*>(values.data()));
}

void LibraryEngine::check_atom_values(std::size_t size, int count, const std::string& name) const {
  if (size != static_cast<std::size_t>(atom_count()) * count)
    throw std::invalid_argument("scatter of '" + name + "': " + std::to_string(size) +
                                " values for " + std::to_string(atom_count()) + " atoms × " +
                                std::to_string(count));
}

long LibraryEngine::ghost_count() const {
  return *static_cast<int*>(lammps_extract_global(handle_, const_cast<char*>("nghost")));
}

std::vector<double> LibraryEngine::gather_local_array(const std::string& compute_id, int local_rows,
                                                      int columns) {
  auto* rows = static_cast<double**>(
      lammps_extract_compute(handle_, const_cast<char*>(compute_id.c_str()), 2, 2));
  std::vector<double> mine(static_cast<std::size_t>(local_rows) * columns);
  for (int r = 0; r < local_rows; ++r)
    for (int c = 0; c < columns; ++c)
      mine[static_cast<std::size_t>(r) * columns + c] = rows[r][c];
  return gather_rows(mine);
}

std::vector<double> LibraryEngine::gather_rows(const std::vector<double>& mine) {
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  const int my_count = static_cast<int>(mine.size());
  std::vector<int> counts(ranks), offsets(ranks, 0);
  MPI_Allgather(&my_count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  for (int r = 1; r < ranks; ++r)
    offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(mine.data(), my_count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, comm_);
  return all;
}

std::vector<Overlap> LibraryEngine::overlaps_of(const std::vector<double>& near_pair_rows) {
  constexpr int kColumns = 4;  // id_i, id_j, radius_i, radius_j
  const std::vector<double> rows = gather_rows(near_pair_rows);
  const std::vector<Vec3> x = positions_by_id();
  const Mat3 h = box().h();
  std::vector<Overlap> result;
  for (std::size_t k = 0; k + kColumns <= rows.size(); k += kColumns) {
    const double* row = &rows[k];
    const long i = static_cast<long>(row[0]), j = static_cast<long>(row[1]);
    const double overlap = row[2] + row[3] - minimum_image(x[j - 1] - x[i - 1], h).norm();
    if (overlap > 0.0)
      result.push_back({i, j, overlap / std::min(row[2], row[3])});
  }
  return result;
}

std::vector<Vec3> LibraryEngine::positions_by_id() {
  const std::vector<double> x = gather_atoms("x", 3);
  std::vector<Vec3> positions(x.size() / 3);
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  return positions;
}

std::vector<std::string> split_script(const std::string& script) {
  std::vector<std::string> lines;
  std::string pending;
  std::size_t start = 0;
  while (start <= script.size()) {
    std::size_t end = script.find('\n', start);
    if (end == std::string::npos)
      end = script.size();
    std::string line = script.substr(start, end - start);
    const std::size_t last = line.find_last_not_of(" \t\r");
    if (last != std::string::npos && line[last] == '&') {
      pending += line.substr(0, last) + " ";
    } else {
      lines.push_back(pending + line);
      pending.clear();
    }
    start = end + 1;
  }
  if (!pending.empty())
    lines.push_back(pending);
  return lines;
}

Vec3 minimum_image(const Vec3& d, const Mat3& h) {
  Vec3 s = h.triangularView<Eigen::Upper>().solve(d);
  for (int k = 0; k < 3; ++k)
    s[k] -= std::nearbyint(s[k]);
  return h * s;
}

}  // namespace mpm_lig::dem::detail
