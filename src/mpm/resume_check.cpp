#include "mpm/resume_check.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "core/build_id.h"
#include "core/case_error.h"
#include "core/printable.h"
#include "io/bundle.h"
#include "io/checkpoint_file.h"
#include "io/field_index.h"
#include "io/file_digest.h"
#include "io/run_folder.h"
#include "mpm/case_fingerprint.h"
#include "mpm/checkpoint_folder.h"
#include "mpm/recorder.h"

namespace mpm_lig::mpm {
namespace {

namespace fs = std::filesystem;

//! Lines of `file` (header included), counting at most `enough`.
long count_lines(const std::string& file, long enough) {
  std::ifstream in(file);
  std::string line;
  long lines = 0;
  while (lines < enough && std::getline(in, line))
    ++lines;
  return lines;
}

std::string joined(const std::vector<std::string>& keys) {
  constexpr std::size_t kShown = 12;
  std::string out;
  for (std::size_t k = 0; k < keys.size() && k < kShown; ++k)
    out += (k == 0 ? "" : ", ") + keys[k];
  if (keys.size() > kShown)
    out += " and " + std::to_string(keys.size() - kShown) + " more";
  return out;
}

void check_case(const MpmCase& c, const std::string& folder) {
  const std::string file = folder + "/" + CheckpointFolder::kCase;
  std::ifstream in(file);
  const nlohmann::json saved = nlohmann::json::parse(in, nullptr, false);
  if (saved.is_discarded())
    throw ResumeError("'" + file + "' cannot be read");
  const std::vector<std::string> changed = changed_case_keys(saved, c.document);
  if (!changed.empty())
    throw ResumeError(
        "the case has changed since checkpoint '" + folder + "' was written: " + joined(changed) +
        " (only the end, output intervals and the title may change on resume; run the changed "
        "case from the start with another --output)");
}

void check_state(const MpmCase& c, const std::string& folder) {
  const io::CheckpointFile state(folder + "/" + CheckpointFolder::kState,
                                 io::CheckpointFile::Mode::read);
  const int format = state.has_attribute("format") ? static_cast<int>(state.get("format")) : 1;
  if (format < CheckpointFolder::kOldestFormat || format > CheckpointFolder::kFormat)
    throw ResumeError("checkpoint '" + folder + "' has layout " + std::to_string(format) + " (" +
                      (format < CheckpointFolder::kOldestFormat ? "an older" : "a newer") +
                      " mpm_lig wrote it); this build reads layouts " +
                      std::to_string(CheckpointFolder::kOldestFormat) + " to " +
                      std::to_string(CheckpointFolder::kFormat) +
                      ": run the case from the start with another --output");
  const std::string bad = state.first_non_finite();
  if (!bad.empty())
    throw ResumeError("checkpoint '" + folder + "' holds a value that is not finite in '" + bad +
                      "' (the run had failed before it was written)");
  const long step = static_cast<long>(state.get("steps"));
  if (c.end_steps > 0 && c.end_steps < step)
    throw ResumeError("analysis.end.steps = " + std::to_string(c.end_steps) +
                      " lies before the checkpoint's step " + std::to_string(step));
  if (c.end_time > 0.0 && c.end_time < state.get("time"))
    throw ResumeError("analysis.end.time lies before the checkpoint's time");
}

//! history.csv's header as this build writes it for case `c`.
std::string history_header(const MpmCase& c) {
  return io::CsvHistory::header(c.dimension == 3 ? Recorder<3>::history_columns(c)
                                                 : Recorder<2>::history_columns(c));
}

void check_results(const MpmCase& c, const std::string& run_dir, const std::string& folder) {
  const io::CheckpointFile state(folder + "/" + CheckpointFolder::kState,
                                 io::CheckpointFile::Mode::read);
  const long rows = static_cast<long>(state.get("history_rows"));
  const std::string history = run_dir + "/history.csv";
  if (!fs::is_regular_file(history))
    throw ResumeError("'" + history + "' is missing: the resumed run would lose its first " +
                      std::to_string(rows) + " rows");
  const long lines = count_lines(history, rows + 1);
  if (lines < rows + 1)
    throw ResumeError("'" + history + "' holds " + std::to_string(lines > 0 ? lines - 1 : 0) +
                      " rows, the checkpoint needs " + std::to_string(rows) +
                      " (cut or replaced after the checkpoint)");
  // A build that writes other columns would append rows that its header does not name.
  std::ifstream in(history);
  std::string header;
  std::getline(in, header);
  const std::string expected = history_header(c);
  if (header != expected)
    throw ResumeError("'" + history + "' has the columns " + header + "; this build writes " +
                      expected +
                      ": resume with the build that started the run, or run the case from the "
                      "start with another --output");
  const std::string fields = run_dir + "/results.h5";
  if (!c.write_fields || !fs::exists(fields))
    return;
  try {
    io::read_field_steps(fields);
  } catch (const std::exception& e) {
    throw ResumeError("'" + fields + "' cannot be read (" + e.what() +
                      "); it is left as it is: move it elsewhere to resume without its fields");
  }
}

//! Another build continues the run: allowed (a fix may be why the user resumes), but its
//! arithmetic may differ from the build that wrote the checkpoint, so the run says so.
void warn_if_other_build(const std::string& folder) {
  std::ifstream in(folder + "/" + CheckpointFolder::kBuild);
  std::string written;
  std::getline(in, written);
  if (written != build_id())
    std::fprintf(stderr,
                 "mpm_lig: warning: checkpoint '%s' was written by build %s, this is build %s: "
                 "the steps after it may differ from a run made by either build alone\n",
                 printable(folder, 300).c_str(),
                 written.empty() ? "(not recorded)" : printable(written, 80).c_str(), build_id());
}

//! A bundle's content is checked member by member against the index (bundle_problem).
bool is_bundle(const std::string& relative) {
  const std::string suffix = ".bundle";
  return relative.size() > suffix.size() &&
         relative.compare(relative.size() - suffix.size(), suffix.size(), suffix) == 0;
}

//! `problem` of rank `root`, on every rank.
std::string share(std::string problem, int root, MPI_Comm comm) {
  int length = static_cast<int>(problem.size());
  MPI_Bcast(&length, 1, MPI_INT, root, comm);
  problem.resize(static_cast<std::size_t>(length));
  MPI_Bcast(problem.data(), length, MPI_CHAR, root, comm);
  return problem;
}

//! Collective: every member of every bundle of checkpoint `folder` read and checked against
//! the SHA-256 its writer recorded in the index, the members dealt out over the ranks (so no
//! rank reads the whole checkpoint); the first rank's problem, or "".
std::string bundle_problem(const MpmCase& c, const std::string& folder, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::string problem;
  try {
    const io::CheckpointFile state(folder + "/" + CheckpointFolder::kState,
                                   io::CheckpointFile::Mode::read);
    for (const int id : c.material_ids) {
      const std::string material = "m" + std::to_string(id);
      if (!state.has(material + "_bundle_index"))
        continue;
      const std::vector<double> index = state.read(material + "_bundle_index");
      const auto per_point =
          static_cast<std::size_t>(state.get(material + "_bundle_members_per_point"));
      if (per_point == 0 || index.size() % (per_point * io::kBundleMemberWidth) != 0)
        throw std::runtime_error("its bundle index of material " + std::to_string(id) +
                                 " is damaged");
      std::vector<io::BundleMember> members;
      for (std::size_t k = 0; k < index.size(); k += io::kBundleMemberWidth)
        members.push_back(io::unpack_member(index.data() + k));
      const std::string bundles = folder + "/" + material;
      if (rank == 0)
        problem = io::bundle_layout_problem(bundles, members);
      for (std::size_t k = static_cast<std::size_t>(rank); problem.empty() && k < members.size();
           k += static_cast<std::size_t>(ranks)) {
        try {
          io::read_member(bundles, members[k]);
        } catch (const std::exception& e) {
          problem = "material " + std::to_string(id) + ", material point " +
                    std::to_string(k / per_point) + ", member " + std::to_string(k % per_point) +
                    ": " + e.what();
        }
      }
      if (!problem.empty())
        break;
    }
  } catch (const std::exception& e) {
    problem = e.what();
  }
  const int mine = problem.empty() ? ranks : rank;
  int first = ranks;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == ranks)
    return "";
  return "checkpoint '" + folder + "' is damaged: " + share(problem, first, comm);
}

std::string resume_problem(const MpmCase& c, const std::string& run_dir) {
  try {
    io::check_run_folder(run_dir);  // a --validate --resume reads without the folder's lock
    const std::string folder = CheckpointFolder::latest(run_dir);
    const std::string damage = io::manifest_problem(folder, CheckpointFolder::kManifest, is_bundle);
    if (!damage.empty())
      return "checkpoint '" + folder + "' is damaged: " + damage;
    check_case(c, folder);
    check_state(c, folder);
    check_results(c, run_dir, folder);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

void check_resume(const MpmCase& c, const std::string& run_dir, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string problem = share(rank == 0 ? resume_problem(c, run_dir) : "", 0, comm);
  if (problem.empty())
    problem = bundle_problem(c, CheckpointFolder::latest(run_dir), comm);
  if (!problem.empty())
    throw ResumeError(problem);
  if (rank == 0)
    warn_if_other_build(CheckpointFolder::latest(run_dir));
}

}  // namespace mpm_lig::mpm
