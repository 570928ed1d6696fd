// mpm_lig: hierarchical MPM x DEM. Command line, case loading and the top-level error policy.
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <mpi.h>

#include "core/analysis.h"
#include "core/build_id.h"
#include "core/case_error.h"
#include "core/case_node.h"
#include "core/mpi_session.h"
#include "core/printable.h"
#include "core/stop_signal.h"
#include "io/run_folder.h"
#include "materials/material.h"
#include "mpm/register.h"
#if MPM_LIG_WITH_DEM
#include "coupling/register.h"
#include "element/register.h"
#endif

namespace {

constexpr const char* kUsage = R"(usage:
  mpm_lig CASE.json [--output DIR] [--replace]      run a case
  mpm_lig CASE.json --resume DIR                    continue a stopped run
  mpm_lig --validate CASE.json                      check the whole case; exit 0 (valid) or 2
  mpm_lig --help                                    this text
  mpm_lig --version                                 this build's identity

  Runs under MPI: mpirun -np N mpm_lig CASE.json
  --output DIR   where results go (default: ./<case name>_out); one run at a time writes
                 a folder, and a folder holding an earlier run's results is refused
  --replace      replace the earlier run's results in the output folder
  --resume DIR   continue the run in DIR from its last checkpoint; the results continue
                 in DIR too (--output, if given as well, must name the same folder)

Exit codes: 0 done, 1 run failed, 2 bad case or command line, 3 a DEM engine failed,
  4 stopped by SIGTERM/SIGINT/SIGHUP (the log says whether a checkpoint was written:
  then continue with --resume DIR).
)";

struct CommandLine {
  std::string case_file;
  std::optional<std::string> output_dir;
  std::optional<std::string> resume_dir;
  bool validate_only = false;
  bool replace = false;
  bool help = false;
  bool version = false;
};

//! Parse argv; a std::nullopt means bad usage (already reported).
std::optional<CommandLine> parse_command_line(int argc, char** argv, bool report) {
  CommandLine cl;
  auto fail = [&](const std::string& what) -> std::optional<CommandLine> {
    if (report)
      std::fprintf(stderr, "mpm_lig: %s\n%s", what.c_str(), kUsage);
    return std::nullopt;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* flag) -> const char* {
      return i + 1 < argc ? argv[++i] : (fail(std::string(flag) + " needs a value"), nullptr);
    };
    if (arg == "--help" || arg == "-h") {
      cl.help = true;
    } else if (arg == "--version") {
      cl.version = true;
    } else if (arg == "--validate") {
      cl.validate_only = true;
    } else if (arg == "--replace") {
      cl.replace = true;
    } else if (arg == "--output" || arg == "-o") {
      const char* v = value("--output");
      if (!v)
        return std::nullopt;
      cl.output_dir = v;
    } else if (arg == "--resume") {
      const char* v = value("--resume");
      if (!v)
        return std::nullopt;
      cl.resume_dir = v;
    } else if (!arg.empty() && arg[0] == '-') {
      return fail("unknown option '" + arg + "'");
    } else if (cl.case_file.empty()) {
      cl.case_file = arg;
    } else {
      return fail("more than one case file given ('" + cl.case_file + "', '" + arg + "')");
    }
  }
  if (!cl.help && !cl.version && cl.case_file.empty())
    return fail("no case file given");
  if (cl.replace && cl.resume_dir)
    return fail("--replace and --resume exclude each other: a resume continues the results");
  return cl;
}

//! The program's analyses and materials: the continuum MPM always; with a DEM engine built,
//! element tests on an RVE and the multiscale "dem_rve" material too.
mpm_lig::AnalysisRegistry make_registry() {
  mpm_lig::AnalysisRegistry registry;
  mpm_lig::materials::MaterialRegistry materials;
  mpm_lig::materials::register_materials(materials);
#if MPM_LIG_WITH_DEM
  mpm_lig::coupling::register_materials(materials);
  mpm_lig::element::register_analyses(registry);
#endif
  mpm_lig::mpm::register_analyses(registry, std::move(materials));
  return registry;
}

//! Validate the whole case and build the analysis (no files, no engines yet).
std::unique_ptr<mpm_lig::Analysis> load_analysis(const std::string& case_file) {
  const auto document = mpm_lig::CaseDocument::load(case_file);
  const mpm_lig::CaseNode root = document.root();
  root.get_or<std::string>("title", "");
  const auto registry = make_registry();
  auto analysis = registry.create(root.child("analysis"), "type", root);
  document.check_all_used();
  return analysis;
}

//! Whether `a` and `b` name one folder; a name the system cannot resolve (too long, a loop
//! of links) sets `refusal` and gives false.
bool same_folder(const std::string& a, const std::string& b, std::string& refusal) {
  namespace fs = std::filesystem;
  try {
    return fs::weakly_canonical(a) == fs::weakly_canonical(b);
  } catch (const fs::filesystem_error& e) {
    refusal = "--output " + a + " / --resume " + b + ": " + e.code().message();
    return false;
  }
}

//! The one rule for the folder a run writes to: --output DIR, else for a resumed run the
//! folder it resumes from (which must exist: nothing is created for a resume), else
//! ./<case name>_out. Refused (a message for the user): an empty name, and --output naming
//! another folder than --resume (the run continues where its checkpoint and earlier results
//! are; copying them elsewhere first is the user's choice, not a silent one).
std::string run_directory(const CommandLine& cl, std::string& refusal) {
  namespace fs = std::filesystem;
  if (cl.output_dir && cl.output_dir->empty())
    refusal = "--output: the folder name is empty";
  else if (cl.resume_dir && cl.resume_dir->empty())
    refusal = "--resume: the folder name is empty";
  else if (std::error_code ignored; cl.resume_dir && !fs::is_directory(*cl.resume_dir, ignored))
    refusal = "--resume " + *cl.resume_dir + ": no such folder";
  else if (cl.resume_dir && cl.output_dir &&
           !same_folder(*cl.output_dir, *cl.resume_dir, refusal) && refusal.empty())
    refusal = "--output " + *cl.output_dir + " and --resume " + *cl.resume_dir +
              " name different folders: a resumed run continues in the folder it resumes "
              "from (copy that folder first to keep it unchanged)";
  if (!refusal.empty())
    return "";
  if (cl.resume_dir)
    return *cl.resume_dir;
  if (cl.output_dir)
    return *cl.output_dir;
  return fs::path(cl.case_file).stem().string() + "_out";
}

//! Rank 0 takes the run's folder (creating it for a new run) and checks that no name in it
//! leads out of it and that a new run loses no earlier results; every rank learns the outcome.
//! On refusal `refusal` says why and nothing in the folder was changed (a folder created here
//! is empty and removed again).
std::unique_ptr<mpm_lig::io::RunFolderLock> take_run_folder(const CommandLine& cl,
                                                            const std::string& dir, bool root_rank,
                                                            std::string& refusal) {
  namespace fs = std::filesystem;
  std::unique_ptr<mpm_lig::io::RunFolderLock> lock;
  int refused = 0;
  if (root_rank) {
    bool created = false;
    try {
      std::error_code ignored;
      created = !cl.resume_dir && !fs::exists(dir, ignored) && fs::create_directories(dir);
      lock = std::make_unique<mpm_lig::io::RunFolderLock>(dir);
      mpm_lig::io::check_run_folder(dir);
      const std::string earlier = cl.resume_dir ? "" : mpm_lig::io::earlier_results(dir);
      if (!earlier.empty() && !cl.replace)
        throw mpm_lig::io::RunFolderRefused("the output folder '" + dir +
                                            "' holds an earlier run's results (" + earlier +
                                            "): continue that run with --resume " + dir +
                                            ", replace its results with "
                                            "--replace, or choose another --output");
      if (!earlier.empty())
        mpm_lig::io::remove_run_outputs(dir);
    } catch (const std::exception& e) {
      refusal = e.what();
      refused = 1;
      lock.reset();
      std::error_code ignored;
      if (created)
        fs::remove(dir, ignored);
    }
  }
  MPI_Bcast(&refused, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (refused && refusal.empty())
    refusal = "refused on rank 0";
  return lock;
}

}  // namespace

int main(int argc, char** argv) {
  // First of all: a signal from here on stops the run cleanly, whatever phase it is in.
  mpm_lig::install_stop_handlers();
  mpm_lig::MpiSession mpi(&argc, &argv);
  const bool root_rank = mpi.rank() == 0;

  const auto cl = parse_command_line(argc, argv, root_rank);
  if (!cl)
    return mpm_lig::kExitBadCase;
  if (cl->help) {
    if (root_rank)
      std::fputs(kUsage, stdout);
    return 0;
  }
  if (cl->version) {
    if (root_rank)
      std::printf("mpm_lig %s\n", mpm_lig::build_id());
    return 0;
  }

  // Everything the run would refuse is found here, before any file exists.
  const std::string case_name = mpm_lig::printable(cl->case_file, 300);
  auto refuse = [&](const std::string& message, int code) {
    if (root_rank)
      std::fprintf(stderr, "mpm_lig: %s\n", mpm_lig::printable(message).c_str());
    return code;
  };
  std::unique_ptr<mpm_lig::Analysis> analysis;
  try {
    analysis = load_analysis(cl->case_file);
  } catch (const mpm_lig::CaseError& e) {
    return refuse(case_name + ": " + e.what(), mpm_lig::kExitBadCase);
  } catch (const std::exception& e) {
    return refuse(case_name + ": internal error while checking the case: " + e.what(), 1);
  }
  if (cl->resume_dir && !analysis->supports_resume())
    return refuse("--resume: this analysis type writes no checkpoints", mpm_lig::kExitBadCase);
  mpm_lig::RunContext context;
  context.case_file = cl->case_file;
  std::string refusal;
  context.output_dir = run_directory(*cl, refusal);
  context.resume = cl->resume_dir.has_value();
  context.hooks = mpm_lig::TestHooks::from_environment();
  if (!refusal.empty())
    return refuse(refusal, mpm_lig::kExitBadCase);
  // A resume takes its folder before it reads the checkpoint there: a live run may be
  // rewriting it, and must be named as the reason, not a checkpoint caught mid-write.
  std::unique_ptr<mpm_lig::io::RunFolderLock> folder_lock;  // rank 0's
  const bool take_first = context.resume && !cl->validate_only;
  if (take_first) {
    folder_lock = take_run_folder(*cl, context.output_dir, root_rank, refusal);
    if (!refusal.empty())
      return refuse(refusal, mpm_lig::kExitBadCase);
  }
  try {
    analysis->check_run(context);
  } catch (const mpm_lig::CaseError& e) {
    return refuse(case_name + ": " + e.what(), mpm_lig::kExitBadCase);
  } catch (const mpm_lig::ResumeError& e) {
    // Refused on every rank alike, before any file was touched.
    return refuse("--resume " + mpm_lig::printable(context.output_dir, 300) + ": " + e.what(),
                  mpm_lig::kExitBadCase);
  }
  if (cl->validate_only) {
    if (root_rank) {
      std::printf("%s: valid\n", case_name.c_str());
      for (const std::string& line : analysis->unchecked())
        std::printf("  checked only when the run gets there: %s\n", line.c_str());
    }
    return 0;
  }

  if (mpm_lig::stop_requested(MPI_COMM_WORLD))
    return refuse("stopped by a signal before the run started: nothing was written",
                  mpm_lig::kExitStopped);
  if (!take_first) {
    folder_lock = take_run_folder(*cl, context.output_dir, root_rank, refusal);
    if (!refusal.empty())
      return refuse(refusal, mpm_lig::kExitBadCase);
  }
  try {
    // A stopped run has said where it stopped and whether its checkpoint was written.
    if (analysis->run(context) == mpm_lig::RunEnd::stopped)
      return mpm_lig::kExitStopped;
  } catch (const mpm_lig::StopRequested& e) {
    // Thrown on every rank alike, where they agreed to stop.
    return refuse(e.what(), mpm_lig::kExitStopped);
  } catch (const mpm_lig::ResumeError& e) {
    // Refused on every rank alike, before any file was touched.
    if (root_rank)
      std::fprintf(stderr, "mpm_lig: --resume %s: %s\n",
                   mpm_lig::printable(context.output_dir, 300).c_str(),
                   mpm_lig::printable(e.what()).c_str());
    return mpm_lig::kExitBadCase;
  } catch (const mpm_lig::ReplicatedError& e) {
    return refuse("run failed: " + std::string(e.what()), 1);
  } catch (const mpm_lig::CaseError& e) {
    // Some problems can only be seen at run time (a restart file that is not there).
    mpm_lig::abort_job(case_name + ": " + mpm_lig::printable(e.what()), mpm_lig::kExitBadCase);
  } catch (const std::exception& e) {
    mpm_lig::abort_job("run failed: " + mpm_lig::printable(e.what()), 1);
  }
  return 0;
}
