#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dem/engine_module.h"

namespace mpm_lig::dem::detail {

//! The Engine handed to callers: forwards every call to the module's engine while
//!  - marking itself as the "current instance", so that an engine that ends the process
//!    (MPI_Finalize/MPI_Abort, see core/mpi_session.h) is reported with its label, rank and
//!    last output;
//!  - capturing what the engine prints outside its screen (LIGGGHTS: "version 3 8" at every
//!    read_restart, "Style collision" warnings at creation) into its output record.
//! docs/DESIGN.md §3.5, §3.6.
class GuardedEngine final : public Engine {
 public:
  //! Creates the module engine (under guard) with `create`.
  GuardedEngine(CreateEngineFn create, MPI_Comm comm, const EngineOptions& options,
                const ModuleOptions& module_options);
  ~GuardedEngine() override;

  std::string name() const override;
  void command(const std::string& line) override;
  void commands(const std::string& script) override;
  Box box() const override;
  long atom_count() const override;
  double compute_scalar(const std::string& compute_id) override;
  std::vector<double> compute_vector(const std::string& compute_id, int length) override;
  std::vector<double> gather_atoms(const std::string& name, int count) override;
  void scatter_atoms(const std::string& name, int count,
                     const std::vector<double>& values) override;
  std::vector<int> gather_atom_ints(const std::string& name, int count) override;
  void scatter_atom_ints(const std::string& name, int count,
                         const std::vector<int>& values) override;
  std::vector<Contact> contacts() override;
  std::vector<Overlap> overlaps() override;
  std::string recent_output() const override;
  void add_velocity_field(const Mat3& gradient, const Vec3& origin, int dimension) override;
  void run_continued(const std::string& deform_fix, int steps) override;

  //! Ghost atoms on this rank (tests: health of periodic boxes).
  long ghost_count() const;
  //! The report printed when this instance ends the job.
  std::string failure_report() const;

 private:
  class Scope;
  //! Run `call`, capturing stdout into the engine's record if `input` reads a restart file.
  template <class Call>
  void with_restart_capture(const std::string& input, Call call);

  std::unique_ptr<ModuleEngine> impl_;
  EngineOptions options_;
  MPI_Comm comm_;
};

//! Installs the fatal reporter (core/mpi_session.h) that describes the current instance.
void install_fatal_reporter();

//! Replace the engine's "Style collision" warnings (one per style, ~242 per instance after
//! the first) by a one-line count; other text is kept as it is.
std::string summarise_style_collisions(const std::string& text);

}  // namespace mpm_lig::dem::detail
