#pragma once

#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "core/case_node.h"
#include "core/registry.h"
#include "core/test_hooks.h"

namespace mpm_lig {

//! Exit code of a run that a signal (SIGTERM/SIGINT/SIGHUP) stopped after writing a checkpoint:
//! not complete, to be continued with --resume (0 is for complete runs only).
inline constexpr int kExitStopped = 4;

//! How run() ended when it did not throw.
enum class RunEnd {
  completed,  //!< every step done and every result written
  stopped,    //!< stopped by a signal; a checkpoint to resume from was written if possible
};

//! What every analysis gets to run: where to write and on which ranks.
struct RunContext {
  std::string case_file;  //!< the case file as given on the command line
  //! The run's one folder (results, checkpoints, packings); created by the application
  //! before run() unless the run resumes (then it is the folder given to --resume).
  std::string output_dir;
  bool resume = false;  //!< continue from the last checkpoint in output_dir
  MPI_Comm comm = MPI_COMM_WORLD;
  TestHooks hooks;  //!< fault injection asked for by the tests (none by default)
};

//! One kind of run (an element test on an RVE, an MPM problem, ...). Constructed from
//! the case by a factory that validates everything it needs, so that `mpm_lig --validate`
//! finds every problem before anything is created; run() then does the work.
class Analysis {
 public:
  virtual ~Analysis() = default;
  //! Checks that need the run and not only the case: the rank count (rank groups, memory per
  //! rank) and the folder the run writes into. Collective over `context.comm`; called by
  //! `mpm_lig --validate` and before a run creates anything; a CaseError on failure, a
  //! ResumeError when the checkpoint of a resume (context.resume) is refused.
  virtual void check_run(const RunContext& /*context*/) const {}
  //! What neither the constructor nor check_run() can know before the run, one line each,
  //! for `mpm_lig --validate` to say (empty: everything was checked).
  virtual std::vector<std::string> unchecked() const { return {}; }
  virtual RunEnd run(const RunContext& context) = 0;
  //! Whether run() can continue from a checkpoint (RunContext::resume).
  virtual bool supports_resume() const { return false; }
};

//! Factories get the case root; they must read every key they accept.
using AnalysisRegistry = Registry<Analysis, const CaseNode&>;

}  // namespace mpm_lig
