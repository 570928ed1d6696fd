#pragma once
// The contract between the loader (linked into the executable) and the engine modules
// (one dlopen'ed shared module per engine library). Internal to src/dem.

#include <mpi.h>

#include <memory>
#include <string>

#include "dem/engine.h"

namespace mpm_lig::dem::detail {

//! What a module's engine offers beyond the public Engine interface.
class ModuleEngine : public Engine {
 public:
  //! Add text the engine printed outside its screen (captured stdout/stderr) to its record,
  //! so that what the loader silenced stays retrievable through recent_output().
  virtual void record_output(const std::string& text) = 0;
  //! Ghost atoms held by this rank (a health check of periodic boxes).
  virtual long ghost_count() const = 0;
};

//! Options a module needs besides the public EngineOptions.
struct ModuleOptions {
  //! Test-only (LIGGGHTS): skip the triclinic-box correction to show the library defect.
  bool skip_triclinic_correction = false;
};

//! The one symbol each module exports: `extern "C" ModuleEngine* mpm_lig_create_engine(...)`.
//! Returns nullptr only if the options are unusable; engine errors end the process (see
//! core/mpi_session.h).
using CreateEngineFn = ModuleEngine* (*)(MPI_Comm comm, const EngineOptions* options,
                                         const ModuleOptions* module_options);
inline constexpr const char* kCreateEngineSymbol = "mpm_lig_create_engine";

//! create_engine (engine.h) with module options (tests use it to show library defects).
std::unique_ptr<Engine> create_engine(const std::string& name, MPI_Comm comm,
                                      const EngineOptions& options,
                                      const ModuleOptions& module_options);

}  // namespace mpm_lig::dem::detail
