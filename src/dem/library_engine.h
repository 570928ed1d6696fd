#pragma once

#include <mpi.h>

#include <string>
#include <vector>

#include "dem/engine_module.h"
#include "dem/output_ring.h"

namespace mpm_lig::dem::detail {

//! What LIGGGHTS and LAMMPS share behind their C library interface (`lammps_command`,
//! `lammps_extract_compute`, `lammps_gather_atoms`, ...). This file is compiled into each
//! engine module against that engine's own `library.h`.
class LibraryEngine : public ModuleEngine {
 public:
  LibraryEngine(MPI_Comm comm, const EngineOptions& options);
  ~LibraryEngine() override;
  LibraryEngine(const LibraryEngine&) = delete;
  LibraryEngine& operator=(const LibraryEngine&) = delete;

  void command(const std::string& line) override;
  void commands(const std::string& script) override;
  double compute_scalar(const std::string& compute_id) override;
  std::vector<double> compute_vector(const std::string& compute_id, int length) override;
  std::vector<double> gather_atoms(const std::string& name, int count) override;
  void scatter_atoms(const std::string& name, int count,
                     const std::vector<double>& values) override;
  std::vector<int> gather_atom_ints(const std::string& name, int count) override;
  void scatter_atom_ints(const std::string& name, int count,
                         const std::vector<int>& values) override;
  std::string recent_output() const override { return output_.text(); }
  //! The three commands (LAMMPS).
  void add_velocity_field(const Mat3& gradient, const Vec3& origin, int dimension) override;
  void record_output(const std::string& text) override { output_.append(text); }
  long ghost_count() const override;

 protected:
  //! Command-line arguments for the engine (screen off; log file if asked for).
  std::vector<std::string> engine_args(const std::string& program) const;
  //! Take ownership of an opened engine and point its screen at the in-memory record.
  void adopt(void* handle, FILE** engine_screen);
  void* handle() const { return handle_; }
  MPI_Comm comm() const { return comm_; }
  //! A local array (rows × columns) of a compute, gathered over the instance's ranks.
  std::vector<double> gather_local_array(const std::string& compute_id, int local_rows,
                                         int columns);
  //! `mine` (rows of any width) from every rank of the instance, rank by rank.
  std::vector<double> gather_rows(const std::vector<double>& mine);
  //! overlaps() from near_pair_rows (neighbour_overlaps.h) of every rank.
  std::vector<Overlap> overlaps_of(const std::vector<double>& near_pair_rows);
  //! Throws unless `size` = atoms × `count`.
  void check_atom_values(std::size_t size, int count, const std::string& name) const;
  //! `run` commands issued so far (set-ups included).
  long runs() const { return runs_; }
  //! Positions of all atoms, ordered by atom id (ids 1..N).
  std::vector<Vec3> positions_by_id();

 private:
  MPI_Comm comm_;
  EngineOptions options_;
  OutputRing output_;
  void* handle_ = nullptr;
  long runs_ = 0;
};

//! Split a script into input lines, joining lines continued with a trailing '&'.
std::vector<std::string> split_script(const std::string& script);

//! The periodic image of `d` nearest to zero for the box with cell matrix `h` (columns =
//! box vectors). Exact for |d| below half the shortest box width, which contacts satisfy.
Vec3 minimum_image(const Vec3& d, const Mat3& h);

}  // namespace mpm_lig::dem::detail
