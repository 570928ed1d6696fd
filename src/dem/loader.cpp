// Finds, loads and opens the engine modules (see engine.h for why they are modules).
#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "dem/engine.h"
#include "dem/engine_module.h"
#include "dem/guarded_engine.h"

namespace mpm_lig::dem {
namespace {

//! Where the modules are: $MPM_LIG_ENGINE_DIR, else next to the running executable (the
//! build puts every binary in one folder; an install puts them in one bin folder).
std::filesystem::path module_directory() {
  if (const char* dir = std::getenv("MPM_LIG_ENGINE_DIR"); dir && *dir)
    return dir;
  return std::filesystem::read_symlink("/proc/self/exe").parent_path();
}

std::string join(const std::vector<std::string>& names) {
  std::string all;
  for (const std::string& n : names)
    all += (all.empty() ? "" : ", ") + n;
  return all;
}

struct LoadedModule {
  detail::CreateEngineFn create = nullptr;
};

//! Loads module `name` once per process. RTLD_LOCAL keeps its engine library's symbols
//! (lammps_*, LAMMPS_NS::*) out of the global scope, so the other module can still bind to
//! its own library. No RTLD_DEEPBIND: the engine library must keep resolving MPI_Finalize
//! and MPI_Abort to the executable's guards (core/mpi_session.cpp), which DEEPBIND would
//! bypass in favour of libmpi's. docs/DESIGN.md §3.1.
detail::CreateEngineFn load_module(const std::string& name) {
  static std::map<std::string, LoadedModule> loaded;
  if (auto it = loaded.find(name); it != loaded.end())
    return it->second.create;
  const std::filesystem::path file = module_directory() / ("mpm_lig_engine_" + name + ".so");
  void* module = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!module)
    throw std::runtime_error("cannot load DEM engine module " + file.string() + ": " + dlerror() +
                             " (set MPM_LIG_ENGINE_DIR to the folder holding the modules)");
  auto create =
      reinterpret_cast<detail::CreateEngineFn>(dlsym(module, detail::kCreateEngineSymbol));
  if (!create)
    throw std::runtime_error(file.string() + " is not a DEM engine module (no " +
                             detail::kCreateEngineSymbol + ")");
  detail::install_fatal_reporter();
  loaded[name].create = create;
  return create;  // modules stay loaded until exit: engine code may run in atexit handlers
}

}  // namespace

std::vector<std::string> engine_names() {
  return {"liggghts", "lammps"};
}

std::unique_ptr<Engine> create_engine(const std::string& name, MPI_Comm comm,
                                      const EngineOptions& options) {
  return detail::create_engine(name, comm, options, detail::ModuleOptions{});
}

namespace detail {

std::unique_ptr<Engine> create_engine(const std::string& name, MPI_Comm comm,
                                      const EngineOptions& options,
                                      const ModuleOptions& module_options) {
  const std::vector<std::string> names = engine_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw std::invalid_argument("unknown DEM engine '" + name + "' (known: " + join(names) + ")");
  return std::make_unique<GuardedEngine>(load_module(name), comm, options, module_options);
}

}  // namespace detail
}  // namespace mpm_lig::dem
