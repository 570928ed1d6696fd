#include "element/element_analysis.h"

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/build_id.h"
#include "core/resources.h"
#include "core/stop_signal.h"
#include "dem/file_name.h"
#include "element/recorded_path.h"
#include "element/strain_path.h"
#include "io/csv_history.h"
#include "io/summary.h"
#include "rve/consolidation.h"
#include "rve/kinematics.h"
#include "rve/rve.h"
#include "rve/snapshot.h"

namespace mpm_lig::element {
namespace {

class ElementTest : public Analysis {
 public:
  ElementTest(rve::RveSpec rve, ElementTestSpec test) : rve_(std::move(rve)), test_(test) {}
  RunEnd run(const RunContext& context) override;

  void check_run(const RunContext& context) const override {
    const std::string unusable = dem::unusable_file_name(context.output_dir);
    if (test_.save_restart && !unusable.empty())
      throw CaseError("analysis.save_restart",
                      "the DEM engine writes prepared.restart into the "
                      "output folder '" +
                          context.output_dir + "': " + unusable);
    int ranks = 1;
    MPI_Comm_size(context.comm, &ranks);
    MemoryBudget budget;
    budget.add("rve.grains", rve::instance_memory_bytes(rve_) / ranks,
               "one RVE of " + std::to_string(rve_.grains) + " grains");
    budget.check(context.comm);
  }

  std::vector<std::string> unchecked() const override {
    return {"rve: the DEM packing (preparation or restart file contents)"};
  }

 private:
  struct Loading;
  class Outputs;

  nlohmann::json describe() const;
  std::unique_ptr<rve::Rve> prepare(const RunContext& context, nlohmann::json& summary);
  double lateral_stiffness(rve::Rve& rve);
  //! The lateral stress a drained test holds: the case's, or the prepared packing's.
  double confining_pressure(const rve::Observables& now) const {
    return test_.confining_pressure > 0.0 ? test_.confining_pressure
                                          : mean_pressure(now.stress, rve_.dimension);
  }
  std::unique_ptr<StrainPath> plan_strain_path(rve::Rve& rve, const rve::Observables& now,
                                               nlohmann::json& summary);
  void stop_if_asked(const RunContext& context, int k, int n, int written) const;
  int apply_increment(rve::Rve& rve, StrainPath& path, int k, Loading& state) const;
  void load(const RunContext& context, rve::Rve& rve, StrainPath& path, Outputs& out,
            Loading& state) const;
  void finish_summary(const RunContext& context, const rve::Rve& rve, const Loading& state,
                      double prepared_steps, double preparation_seconds,
                      nlohmann::json& summary) const;

  rve::RveSpec rve_;
  ElementTestSpec test_;
};

//! The history columns; a recorded path adds `path_time`, the recorded time of the row.
std::vector<std::string> history_columns(bool recorded) {
  std::vector<std::string> columns = {"increment", "time"};
  for (const char* c : kVoigtNames)
    columns.push_back(std::string("e_") + c);
  for (const char* c : kVoigtNames)
    columns.push_back(std::string("s_") + c);
  for (const char* c : {"p", "q", "e_vol", "gamma_xy", "void_ratio", "coordination_number",
                        "kinetic_ratio", "substeps", "flow_ratio", "step_travel", "max_overlap"})
    columns.push_back(c);
  if (recorded)
    columns.push_back("path_time");
  return columns;
}

std::vector<double> history_row(int increment, double time, const Mat3& F,
                                const rve::Observables& o, int dimension, int substeps) {
  std::vector<double> row = {double(increment), time};
  for (double e : to_voigt(hencky_strain(F)))
    row.push_back(e);
  for (double s : to_voigt(o.stress))
    row.push_back(s);
  row.push_back(mean_pressure(o.stress, dimension));
  row.push_back(deviatoric_stress(o.stress, dimension));
  row.push_back(std::log(F.determinant()));
  row.push_back(F(0, 1) / F(1, 1));
  row.push_back(o.void_ratio);
  row.push_back(o.coordination_number);
  row.push_back(o.kinetic_ratio());
  row.push_back(substeps);
  row.push_back(o.flow_ratio());
  row.push_back(o.step_travel);
  row.push_back(o.max_overlap_ratio);
  return row;
}

//! Mobilised friction angle from the extreme principal stresses (compression positive).
double mobilised_friction_deg(const Mat3& sigma, int dimension) {
  const auto [s1, s3] = extreme_principal_stresses(sigma, dimension);
  return std::asin((s1 - s3) / (s1 + s3)) * 180.0 / kPi;
}

nlohmann::json state_json(const rve::Observables& o, int dimension) {
  return {{"p", mean_pressure(o.stress, dimension)},
          {"q", deviatoric_stress(o.stress, dimension)},
          {"stress", to_voigt(o.stress)},
          {"void_ratio", o.void_ratio},
          {"coordination_number", o.coordination_number},
          {"kinetic_ratio", o.kinetic_ratio()}};
}

//! How well a drained test held its lateral stress, over all increments.
class LateralControl {
 public:
  LateralControl(double confining, int dimension)
      : confining_(confining), lateral_axes_(dimension - 1) {}
  void add(const Mat3& stress, int corrections) {
    for (int i = 0; i < lateral_axes_; ++i) {
      const double error = std::abs(-stress(i, i) - confining_) / confining_;
      max_error_ = std::max(max_error_, error);
      sum_squares_ += error * error;
      ++samples_;
    }
    corrections_ += corrections;
    ++increments_;
  }
  nlohmann::json json(double tolerance) const {
    return {{"tolerance", tolerance},
            {"max_relative_error", max_error_},
            {"rms_relative_error", samples_ ? std::sqrt(sum_squares_ / samples_) : 0.0},
            {"corrections_per_increment",
             increments_ ? double(corrections_) / double(increments_) : 0.0}};
  }

 private:
  double confining_;
  int lateral_axes_;
  double max_error_ = 0.0, sum_squares_ = 0.0;
  long samples_ = 0, corrections_ = 0, increments_ = 0;
};

std::unique_ptr<rve::Rve> ElementTest::prepare(const RunContext& context, nlohmann::json& summary) {
  if (!rve_.restart_file.empty()) {
    auto rve = rve::Rve::from_restart(rve_, rve_.restart_file, context.comm, "RVE 0");
    summary["preparation"] = {{"restart_file", rve_.restart_file}};
    return rve;
  }
  auto rve = rve::Rve::generate(rve_, context.comm, "RVE 0");
  const rve::ConsolidationResult c = rve::consolidate(*rve);
  const double p = mean_pressure(c.final.stress, rve_.dimension);
  const double target = rve_.preparation.confining_pressure;
  summary["preparation"] = {{"target_pressure", target},
                            {"pressure", p},
                            {"relative_error", (p - target) / target},
                            {"void_ratio", c.final.void_ratio},
                            {"coordination_number", c.final.coordination_number},
                            {"friction_used", c.friction_used},
                            {"dem_steps", c.steps},
                            {"time_step", rve_.preparation.time_step},
                            {"target_void_ratio_reached", c.void_ratio_reached}};
  if (rve_.preparation.target_void_ratio) {
    summary["preparation"]["target_void_ratio"] = *rve_.preparation.target_void_ratio;
    summary["preparation"]["void_ratio_error"] = c.void_ratio_error;
    summary["preparation"]["compacted_void_ratio"] = c.compacted_void_ratio;
    summary["preparation"]["void_ratio_tolerance"] = rve_.preparation.void_ratio_tolerance;
  }
  int rank = 0;
  MPI_Comm_rank(context.comm, &rank);
  // A missed target ends the run, with the miss in the summary for the record.
  if (!c.void_ratio_reached && rank == 0)
    io::write_json((std::filesystem::path(context.output_dir) / "summary.json").string(), summary);
  rve::require_void_ratio(*rve, c);
  if (test_.save_restart)
    rve->write_restart((std::filesystem::path(context.output_dir) / "prepared.restart").string());
  rve->orient_cell();
  rve->use_loading_time_step();
  return rve;
}

//! dσ/dε of an isotropic probe (per-axis strain, all axes): an upper bound of the lateral
//! stiffness, so that the drained servo never over-corrects.
double ElementTest::lateral_stiffness(rve::Rve& rve) {
  const double probe = test_.strain_increment;
  const double p0 = mean_pressure(rve.stress(), rve_.dimension);
  Mat3 dF = Mat3::Identity() * std::exp(-probe);
  if (rve_.dimension == 2)
    dF(2, 2) = 1.0;
  rve.deform(dF);
  const double p1 = mean_pressure(rve.stress(), rve_.dimension);
  rve.deform(dF.inverse());
  return std::max((p1 - p0) / probe, 10.0 * std::abs(p0));
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

//! Where the loading stands after an increment.
struct ElementTest::Loading {
  Mat3 F = Mat3::Identity();
  double time = 0.0;
  rve::Observables now;
  int written = 0;  //!< the last increment in history.csv
  double peak_friction = 0.0;
  nlohmann::json peak;
  LateralControl lateral;
  int substeps = 0;     //!< of the last increment, its corrections included
  int corrections = 0;  //!< of the last increment

  Loading(const rve::Observables& start, double confining, int dimension)
      : now(start),
        peak_friction(mobilised_friction_deg(start.stress, dimension)),
        peak(state_json(start, dimension)),
        lateral(confining, dimension) {}
};

//! What an element test writes as it loads (rank 0): history.csv and the RVE snapshots.
class ElementTest::Outputs {
 public:
  Outputs(const RunContext& context, rve::Rve& rve, int dimension, const RecordedPath* recorded)
      : dir_(context.output_dir), rve_(rve), dimension_(dimension), recorded_(recorded) {
    int rank = 0;
    MPI_Comm_rank(context.comm, &rank);
    writer_ = rank == 0;
    if (!writer_)
      return;
    history_ = std::make_unique<io::CsvHistory>((dir_ / "history.csv").string(),
                                                history_columns(recorded_ != nullptr));
    std::filesystem::create_directories(dir_ / "snapshots");
  }
  void history(int k, const Loading& s) {
    if (!writer_)
      return;
    std::vector<double> row = history_row(k, s.time, s.F, s.now, dimension_, s.substeps);
    if (recorded_)
      row.push_back(recorded_->time[k]);
    history_->write(row);
  }
  //! Collective over the RVE's ranks.
  void snapshot(int k) {
    char name[32];
    std::snprintf(name, sizeof(name), "rve_%06d", k);
    rve::write_snapshot(rve_, (dir_ / "snapshots" / name).string(), writer_);
  }

 private:
  std::filesystem::path dir_;
  rve::Rve& rve_;
  int dimension_;
  const RecordedPath* recorded_;  //!< a recorded path's rows, or null
  bool writer_ = false;
  std::unique_ptr<io::CsvHistory> history_;
};

//! Where a recorded path came from and how it was replayed.
nlohmann::json recorded_summary(const RecordedPath& p) {
  nlohmann::json j = {{"file", p.source}, {"rows", p.F.size()}};
  if (p.point >= 0)
    j["point"] = p.point;
  long exact = 0, fixed = 0;
  for (std::size_t k = 0; k < p.intervals(); ++k) {
    exact += p.recorded_increment[k].has_value();
    fixed += p.substeps[k] > 0;
  }
  j["recorded_increments"] = exact;  // applied as recorded, not as F_{k+1} F_k^-1
  j["volume"] = p.free_volume ? "free" : "recorded";
  if (p.free_volume)
    j["pressure_tolerance"] = p.pressure_tolerance;
  j["recorded_substeps"] = fixed;  // run with the file's sub-steps, not the RVE's rule
  return j;
}

nlohmann::json ElementTest::describe() const {
  return {{"engine", rve_.engine},
          {"test", test_.name},
          {"dimension", rve_.dimension},
          {"grains", rve_.grains},
          {"time_step", rve_.time_step},
          {"rayleigh_time_step", rve_.rayleigh_time_step},
          {"affine_motion", rve_.stream_velocity ? "streaming_velocity" : "remap_positions"}};
}

//! The test's strain path from the prepared state `now` (a drained test measures its servo's
//! stiffness first).
std::unique_ptr<StrainPath> ElementTest::plan_strain_path(rve::Rve& rve,
                                                          const rve::Observables& now,
                                                          nlohmann::json& summary) {
  double stiffness = 0.0;
  if (test_.kind == TestKind::kDrainedCompression) {
    stiffness = lateral_stiffness(rve);
    summary["confining_pressure"] = confining_pressure(now);
    summary["servo_stiffness"] = stiffness;
  } else if (test_.recorded && test_.recorded->free_volume) {
    stiffness = lateral_stiffness(rve);
    summary["servo_stiffness"] = stiffness;
  }
  return make_strain_path(test_, rve_.dimension, confining_pressure(now), stiffness);
}

void ElementTest::stop_if_asked(const RunContext& context, int k, int n, int written) const {
  if (stop_requested(context.comm))
    throw StopRequested("stopped by a signal after increment " + std::to_string(k) + " of " +
                        std::to_string(n) + ": " + context.output_dir +
                        "/history.csv holds increments 0 ... " + std::to_string(written) +
                        ", no summary.json (an element test writes no checkpoints: run it "
                        "again with --replace)");
}

//! Increment `k` of the path and its corrections; returns the DEM sub-steps it took.
int ElementTest::apply_increment(rve::Rve& rve, StrainPath& path, int k, Loading& state) const {
  const Mat3 dF = path.increment(k, state.now.stress);
  // rve.setup_every: the engine's set-up before one increment in setup_every (with its
  // corrections), the others continue its run.
  const rve::Rve::EngineRun run = rve::update_engine_run(rve_);
  if (rve::starts_setup_period(rve_, k))
    rve.require_setup();
  // A recorded path's increment runs the sub-steps its file gives, else (0) the RVE's rule:
  // the rule the coupling applies to an MPM point's update.
  int substeps = rve.deform(dF, path.substeps(k), run);
  state.F = dF * state.F;
  // Stress-controlled directions: correct within the increment until on target. Each
  // correction takes the sub-steps the RVE's rule gives for its strain (the same inertial
  // number as the increment): measured on the quickstart case, 1.8 corrections per increment
  // cost 6 % more DEM steps; as many sub-steps as the increment itself needed 2.6
  // corrections and 55 % more.
  Mat3 stress = rve.stress();
  int corrections = 0;
  for (std::optional<Mat3> c;
       corrections < test_.max_corrections && (c = path.correction(stress)).has_value();
       ++corrections) {
    substeps += rve.deform(*c, 0, run);
    state.F = *c * state.F;
    stress = rve.stress();
  }
  state.corrections = corrections;
  return substeps;
}

void ElementTest::load(const RunContext& context, rve::Rve& rve, StrainPath& path, Outputs& out,
                       Loading& state) const {
  int rank = 0;
  MPI_Comm_rank(context.comm, &rank);
  const int n = path.increments();
  for (int k = 0; k < n; ++k) {
    stop_if_asked(context, k, n, state.written);
    state.substeps = apply_increment(rve, path, k, state);
    state.time += state.substeps * rve_.time_step;
    state.now = rve.observe();
    if (test_.kind == TestKind::kDrainedCompression)
      state.lateral.add(state.now.stress, state.corrections);
    rve.check_health(state.now);
    const bool last = k + 1 == n;
    if ((k + 1) % test_.output_every == 0 || last) {
      out.history(k + 1, state);
      state.written = k + 1;
    }
    context.hooks.at(TestHooks::Moment::step_recorded, k + 1, rank);
    if ((test_.snapshot_every > 0 && (k + 1) % test_.snapshot_every == 0) || last)
      out.snapshot(k + 1);
    const double phi = mobilised_friction_deg(state.now.stress, rve_.dimension);
    if (phi > state.peak_friction) {
      state.peak_friction = phi;
      state.peak = state_json(state.now, rve_.dimension);
      state.peak["increment"] = k + 1;
    }
  }
}

void ElementTest::finish_summary(const RunContext& context, const rve::Rve& rve,
                                 const Loading& state, double prepared_steps,
                                 double preparation_seconds, nlohmann::json& summary) const {
  if (test_.kind == TestKind::kDrainedCompression)
    summary["lateral_stress"] = state.lateral.json(test_.confining_tolerance);
  summary["final"] = state_json(state.now, rve_.dimension);
  summary["peak"] = state.peak;
  summary["peak_mobilised_friction_deg"] = state.peak_friction;
  double steps[2] = {rve.particle_steps() - prepared_steps, prepared_steps};
  MPI_Allreduce(MPI_IN_PLACE, steps, 2, MPI_DOUBLE, MPI_MAX, context.comm);
  summary["dem_particle_steps"] = steps[0];
  if (summary.contains("preparation"))
    summary["preparation"]["dem_particle_steps"] = steps[1];
  int ranks = 1;
  MPI_Comm_size(context.comm, &ranks);
  // As the MPM summary: cost tools count stepping time (wall minus preparation) per core.
  summary["ranks"] = ranks;
  summary["build"] = build_id();
  summary["time_split"] = {{"preparation", preparation_seconds}};
}

RunEnd ElementTest::run(const RunContext& context) {
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json summary = describe();
  auto rve = prepare(context, summary);
  // The test's own DEM work: the preparation's is reported with it (as an MPM run counts only
  // its main stage), so that cost models see the stepping alone.
  const double prepared_steps = rve->particle_steps();
  const double preparation_seconds = seconds_since(start);
  const rve::Observables prepared = rve->observe();
  rve->check_health(prepared);
  const auto path = plan_strain_path(*rve, prepared, summary);
  Loading state(prepared, confining_pressure(prepared), rve_.dimension);
  state.F = path->start();
  Outputs out(context, *rve, rve_.dimension, test_.recorded.get());
  out.history(0, state);
  out.snapshot(0);
  load(context, *rve, *path, out, state);
  summary["increments"] = path->increments();
  if (test_.recorded)
    summary["path"] = recorded_summary(*test_.recorded);
  finish_summary(context, *rve, state, prepared_steps, preparation_seconds, summary);
  summary["wall_seconds"] = seconds_since(start);
  int rank = 0;
  MPI_Comm_rank(context.comm, &rank);
  if (rank == 0)
    io::write_json((std::filesystem::path(context.output_dir) / "summary.json").string(), summary);
  return RunEnd::completed;
}

}  // namespace

std::unique_ptr<Analysis> make_element_test(const CaseNode& root) {
  rve::RveSpec rve = rve::parse_rve_spec(root.child("rve"));
  ElementTestSpec test = parse_element_test(root.child("analysis"), rve);
  return std::make_unique<ElementTest>(std::move(rve), test);
}

}  // namespace mpm_lig::element
