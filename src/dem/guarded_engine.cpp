#include "dem/guarded_engine.h"

#include <sstream>

#include "core/mpi_session.h"
#include "dem/fd_capture.h"

namespace mpm_lig::dem::detail {
namespace {

const GuardedEngine* g_current = nullptr;  // the instance inside an engine call, if any
constexpr int kReportLines = 25;

std::string last_lines(const std::string& text, int count) {
  std::size_t pos = text.size();
  if (pos > 0 && text[pos - 1] == '\n')
    --pos;
  for (int i = 0; i < count; ++i) {
    const std::size_t nl = pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
    if (nl == std::string::npos)
      return text;
    pos = nl;
  }
  return text.substr(pos + 1);
}

}  // namespace

//! Marks the instance as current for the duration of one engine call (calls may nest:
//! contacts() issues commands).
class GuardedEngine::Scope {
 public:
  explicit Scope(const GuardedEngine* engine) : previous_(g_current) { g_current = engine; }
  ~Scope() { g_current = previous_; }
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  const GuardedEngine* previous_;
};

GuardedEngine::GuardedEngine(CreateEngineFn create, MPI_Comm comm, const EngineOptions& options,
                             const ModuleOptions& module_options)
    : options_(options), comm_(comm) {
  Scope scope(this);
  FdCapture capture(true, true);
  impl_.reset(create(comm, &options, &module_options));
  const std::string printed = summarise_style_collisions(capture.finish());
  if (impl_ && !printed.empty())
    impl_->record_output(printed);
}

GuardedEngine::~GuardedEngine() {
  Scope scope(this);
  impl_.reset();
}

std::string GuardedEngine::name() const {
  return impl_->name();
}

void GuardedEngine::command(const std::string& line) {
  Scope scope(this);
  with_restart_capture(line, [&] { impl_->command(line); });
}

void GuardedEngine::commands(const std::string& script) {
  Scope scope(this);
  with_restart_capture(script, [&] { impl_->commands(script); });
}

template <class Call>
void GuardedEngine::with_restart_capture(const std::string& input, Call call) {
  if (input.find("read_restart") == std::string::npos)
    return call();
  FdCapture capture(true, false);
  call();
  impl_->record_output(capture.finish());
}

Box GuardedEngine::box() const {
  Scope scope(this);
  return impl_->box();
}

long GuardedEngine::atom_count() const {
  Scope scope(this);
  return impl_->atom_count();
}

double GuardedEngine::compute_scalar(const std::string& compute_id) {
  Scope scope(this);
  return impl_->compute_scalar(compute_id);
}

std::vector<double> GuardedEngine::compute_vector(const std::string& compute_id, int length) {
  Scope scope(this);
  return impl_->compute_vector(compute_id, length);
}

std::vector<double> GuardedEngine::gather_atoms(const std::string& name, int count) {
  Scope scope(this);
  return impl_->gather_atoms(name, count);
}

void GuardedEngine::scatter_atoms(const std::string& name, int count,
                                  const std::vector<double>& values) {
  Scope scope(this);
  impl_->scatter_atoms(name, count, values);
}

std::vector<int> GuardedEngine::gather_atom_ints(const std::string& name, int count) {
  Scope scope(this);
  return impl_->gather_atom_ints(name, count);
}

void GuardedEngine::scatter_atom_ints(const std::string& name, int count,
                                      const std::vector<int>& values) {
  Scope scope(this);
  impl_->scatter_atom_ints(name, count, values);
}

std::vector<Contact> GuardedEngine::contacts() {
  Scope scope(this);
  return impl_->contacts();
}

std::vector<Overlap> GuardedEngine::overlaps() {
  Scope scope(this);
  return impl_->overlaps();
}

void GuardedEngine::add_velocity_field(const Mat3& gradient, const Vec3& origin, int dimension) {
  Scope scope(this);
  impl_->add_velocity_field(gradient, origin, dimension);
}

void GuardedEngine::run_continued(const std::string& deform_fix, int steps) {
  Scope scope(this);
  impl_->run_continued(deform_fix, steps);
}

long GuardedEngine::ghost_count() const {
  Scope scope(this);
  return impl_->ghost_count();
}

std::string GuardedEngine::recent_output() const {
  return impl_ ? impl_->recent_output() : std::string();
}

std::string GuardedEngine::failure_report() const {
  int world_rank = 0, world_size = 1, rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  std::ostringstream out;
  out << "DEM engine failure in "
      << (options_.label.empty() ? "an unlabelled instance" : options_.label) << " (engine "
      << (impl_ ? impl_->name() : "being created") << ", MPI rank " << world_rank << " of "
      << world_size << ", rank " << rank << " of " << size << " in the instance's communicator)";
  if (!options_.log_file.empty())
    out << "; engine log: " << options_.log_file;
  const std::string output = recent_output();
  out << "\nlast engine output:\n"
      << (output.empty() ? "(none)\n" : last_lines(output, kReportLines));
  return out.str();
}

void install_fatal_reporter() {
  set_fatal_reporter([]() -> std::string {
    if (!g_current)
      return {};
    FdCapture::restore_active();  // the report must reach the real stderr
    return g_current->failure_report();
  });
}

std::string summarise_style_collisions(const std::string& text) {
  std::istringstream in(text);
  std::string line, kept;
  int collisions = 0;
  while (std::getline(in, line)) {
    if (line.find("Style collision") != std::string::npos)
      ++collisions;
    else
      kept += line + "\n";
  }
  if (collisions > 0)
    kept += "[" + std::to_string(collisions) +
            " 'Style collision' warnings of the engine library not shown]\n";
  return kept;
}

}  // namespace mpm_lig::dem::detail
