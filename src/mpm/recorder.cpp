#include "mpm/recorder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "core/build_id.h"
#include "io/atomic_file.h"
#include "io/summary.h"

namespace mpm_lig::mpm {
namespace {

const char* const kAxisNames[] = {"x", "y", "z"};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string footing_prefix(std::size_t k) {
  return k == 0 ? "" : "footing" + std::to_string(k) + "_";
}

//! Keep the header and the first `rows` data rows of a CSV file. The cut copy is written and
//! checked beside it, then renamed over it: a failure (full disk) leaves the file as it was.
void truncate_rows(const std::string& filename, long rows) {
  std::ifstream in(filename);
  std::string kept, line;
  long lines = 0;
  for (; lines <= rows && std::getline(in, line); ++lines)
    kept += line + '\n';
  in.close();
  if (lines != rows + 1)
    throw std::runtime_error("'" + filename + "' holds fewer rows than the checkpoint");
  io::replace_file(filename, kept, ".resume_tmp");
}

//! DIR/history.csv, cut to the checkpoint's rows for a resumed run.
std::string history_file(const std::string& directory, const RecorderState* resume) {
  const std::string file = directory + "/history.csv";
  if (resume)
    truncate_rows(file, resume->history_rows);
  return file;
}

//! results.h5 of a new run, or continued after the checkpoint (null without field output).
std::unique_ptr<io::FieldWriter> open_fields(const MpmCase& c, const std::string& directory,
                                             long step, const RecorderState* resume) {
  if (!c.write_fields)
    return nullptr;
  if (resume)
    return io::FieldWriter::resume(directory, "results", step);
  return std::make_unique<io::FieldWriter>(directory, "results");
}

//! Simple-shear columns from the points of material `shear.material`: the cycle (1, 2, ...)
//! of the driving function the time lies in (a row at the end of a cycle belongs to it), the
//! engineering shear strain γ = F_xy averaged over the initial volumes (for simple shear the
//! top displacement over the height), τ = σ_xy and p' = −(σ_xx + σ_yy)/2 of the
//! volume-averaged Cauchy stress (τ > 0 for γ > 0, p' compression positive).
template <int D>
void append_simple_shear(const Solver<D>& solver, const SimpleShearOutput& shear,
                         std::vector<double>& row) {
  const Particles<D>& p = solver.particles();
  double v0 = 0.0, v = 0.0, gamma = 0.0;
  Mat3 stress = Mat3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.material[k] != shear.material)
      continue;
    v0 += p.volume0[k];
    gamma += p.volume0[k] * p.deformation[k](0, 1);
    v += p.volume[k];
    stress += p.volume[k] * p.stress[k];
  }
  stress /= v;
  const double cycles = solver.time() / shear.period;
  row.push_back(std::max(1.0, std::ceil(cycles - 1e-6)));
  row.push_back(gamma / v0);
  row.push_back(stress(0, 1));
  row.push_back(-0.5 * (stress(0, 0) + stress(1, 1)));
}

}  // namespace

template <int D>
std::vector<std::string> Recorder<D>::history_columns(const MpmCase& c) {
  std::vector<std::string> columns = {"step", "time", "kinetic_energy"};
  for (std::size_t k = 0; k < c.footings.size(); ++k) {
    // "q" is the footing's bearing pressure (load / contact area), the name geotechnical
    // load-settlement plots use; users' scripts read it, so it keeps that name.
    for (const char* name : {"settlement", "load", "q"})
      columns.push_back(footing_prefix(k) + name);
  }
  for (const Constraint& bc : c.constraints) {
    for (int d = 0; d < D; ++d)
      columns.push_back("bc" + std::to_string(bc.case_index) + "_f" + kAxisNames[d]);
  }
  if (c.simple_shear.enabled) {
    for (const char* name : {"cycle", "shear_strain", "shear_stress", "mean_stress"})
      columns.push_back(name);
  }
  if (c.has_second_gradient())
    columns.push_back("gradient_energy");
  if (c.has_bounded_gradient())
    columns.push_back("gradient_dissipation");
  if (c.record_damping_work)
    columns.push_back("damping_work");
  return columns;
}

template <int D>
std::vector<double> Recorder<D>::history_row(const Solver<D>& solver,
                                             const SimpleShearOutput& shear) {
  std::vector<double> row = {static_cast<double>(solver.steps()), solver.time(),
                             solver.kinetic_energy()};
  for (const auto& f : solver.footings()) {
    row.push_back(f.settlement());
    row.push_back(f.load());
    row.push_back(f.load() / f.contact_area());
  }
  for (std::size_t k = 0; k < solver.constraints().count(); ++k) {
    for (int d = 0; d < D; ++d)
      row.push_back(solver.constraints().reaction(k)[d]);
  }
  if (shear.enabled)
    append_simple_shear(solver, shear, row);
  if (solver.has_second_gradient())
    row.push_back(solver.gradient_energy());
  if (solver.has_second_gradient() && solver.second_gradient()->bounded())
    row.push_back(solver.gradient_dissipation());
  if (solver.records_damping_work())
    row.push_back(solver.damping_work());
  return row;
}

template <int D>
Recorder<D>::Recorder(const MpmCase& c, const Solver<D>& solver, const std::string& directory,
                      long total_steps, const RecorderState* resume)
    : directory_(directory),
      output_every_(c.output_every),
      history_every_(c.history_every),
      total_steps_(total_steps),
      material_ids_(c.material_ids),
      simple_shear_(c.simple_shear),
      write_deformation_(c.write_deformation),
      fields_(open_fields(c, directory, solver.steps(), resume)),
      history_(history_file(directory, resume), history_columns(c), resume != nullptr),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {
  if (!resume) {
    after_step(solver);
    return;
  }
  history_rows_ = resume->history_rows;
  peak_bearing_pressure_ = resume->peak_bearing_pressure;
  largest_stiffened_cfl_ = resume->largest_stiffened_cfl;
  last_step_ = solver.steps();
  // The restored materials carry the run's totals so far: the first progress line's rates
  // count only what was done after the resume.
  last_statistics_ = solver.materials().statistics();
}

template <int D>
void Recorder<D>::after_step(const Solver<D>& solver) {
  const auto start = std::chrono::steady_clock::now();
  const long step = solver.steps();
  for (const auto& f : solver.footings())
    peak_bearing_pressure_ = std::max(peak_bearing_pressure_, f.load() / f.contact_area());
  watch_stiffened_cfl(solver);
  if (step % history_every_ == 0 || step == total_steps_) {
    history_.write(history_row(solver, simple_shear_));
    ++history_rows_;
  }
  if (step % output_every_ == 0 || step == total_steps_) {
    if (fields_)
      write_fields(solver);
    if (step > 0)
      print_progress(solver);
  }
  output_seconds_ += seconds_since(start);
}

// The step is set once, from the materials' moduli at the start; packings stiffen with their
// pressure (under a footing 5-20 times the initial), and a DEM-backed column stable at CFL 0.5
// was unstable from 0.6 on (docs/testing.md, Hard cases): say so once when the step has grown
// past that for the material, and keep the largest for the summary.
template <int D>
void Recorder<D>::watch_stiffened_cfl(const Solver<D>& solver) {
  const double cfl = solver.stiffened_cfl();
  largest_stiffened_cfl_ = std::max(largest_stiffened_cfl_, cfl);
  double limit = 1.0;
  for (std::size_t m = 0; m < solver.materials().size(); ++m)
    limit = std::min(limit, solver.materials()[m]->max_cfl());
  constexpr double kUnstableAbove = 1.2;  // of the measured stable limit
  if (warned_stiffened_ || cfl <= kUnstableAbove * limit)
    return;
  warned_stiffened_ = true;
  std::fprintf(stderr,
               "mpm_lig: warning: at step %ld the time step is CFL %.3f of the materials' "
               "fastest wave as their state has stiffened them, above the %.2f measured "
               "unstable; the answer may carry a bounded instability (docs/methods.md §7): a "
               "smaller time step keeps it stable\n",
               solver.steps(), cfl, kUnstableAbove * limit);
}

template <int D>
void Recorder<D>::write_fields(const Solver<D>& solver) {
  const Particles<D>& p = solver.particles();
  const std::size_t n = p.size();
  std::vector<Vec3> position(n), displacement(n), velocity(n);
  std::vector<Mat3> strain(n);
  std::vector<double> eps_q(n);
  std::vector<int> material(n);
  for (std::size_t k = 0; k < n; ++k) {
    position[k].setZero();
    displacement[k].setZero();
    velocity[k].setZero();
    position[k].template head<D>() = p.position[k];
    displacement[k].template head<D>() = p.position[k] - p.reference[k];
    velocity[k].template head<D>() = p.velocity[k];
    strain[k] = hencky_strain(p.deformation[k]);
    eps_q[k] = deviatoric_strain(strain[k]);
    material[k] = material_ids_[p.material[k]];
  }
  fields_->begin_step(solver.steps(), solver.time(), position);
  fields_->add_vector("displacement", displacement);
  fields_->add_vector("velocity", velocity);
  fields_->add_tensor("stress", p.stress);
  fields_->add_tensor("strain", strain);
  fields_->add_scalar("deviatoric_strain", eps_q);
  fields_->add_scalar("volume", p.volume);
  fields_->add_int("material", material);
  if (write_deformation_) {
    fields_->add_matrix("deformation_gradient", p.deformation);
    // The increment the step that ended here gave every material, exactly: a replay of a point
    // recorded every step applies these bits instead of F_{k+1} F_k^-1, which differs from them
    // by round-off (docs/methods.md §6). None yet before the first main-stage step.
    if (solver.steps() == 0)
      fields_->add_matrix("deformation_increment", std::vector<Mat3>(n, Mat3::Identity()));
    else
      fields_->add_matrix("deformation_increment", solver.increments());
  }
  // Material state variables (plastic strain, ...): zero on points of other materials.
  for (std::size_t m = 0; m < solver.materials().size(); ++m) {
    const auto& mat = *solver.materials()[m];
    const auto names = mat.state_names();
    for (std::size_t s = 0; s < names.size(); ++s) {
      std::vector<double> values(n, 0.0);
      for (std::size_t k = 0; k < n; ++k) {
        if (p.material[k] == static_cast<int>(m))
          values[k] = mat.state(p.material_point[k], s);
      }
      fields_->add_scalar(names[s] + "_m" + std::to_string(material_ids_[m]), values);
    }
  }
  fields_->end_step();
}

template <int D>
void Recorder<D>::print_progress(const Solver<D>& solver) {
  const double interval = seconds_since(last_);
  const double rate = (solver.steps() - last_step_) / std::max(interval, 1e-9);
  const double eta = (total_steps_ - solver.steps()) / std::max(rate, 1e-9);
  const materials::Statistics statistics = solver.materials().statistics();
  std::string items;
  for (const std::string& item : statistics.progress(last_statistics_, std::max(interval, 1e-9)))
    items += "  " + item;
  if (!items.empty())
    std::printf("mpm step %ld/%ld  t = %.6g s  %.3g steps/s%s  ETA %.1f s\n", solver.steps(),
                total_steps_, solver.time(), rate, items.c_str(), eta);
  else
    std::printf("mpm step %ld/%ld  t = %.6g s  %.0f steps/s  ETA %.1f s\n", solver.steps(),
                total_steps_, solver.time(), rate, eta);
  std::fflush(stdout);
  last_statistics_ = statistics;
  last_ = std::chrono::steady_clock::now();
  last_step_ = solver.steps();
}

template <int D>
void Recorder<D>::finish(const Solver<D>& solver, const RunTotals& totals) {
  materials::Statistics statistics = totals.statistics;
  statistics.set_wall_seconds(totals.wall_seconds);
  nlohmann::json s;
  s["wall_seconds"] = totals.wall_seconds;
  s["ranks"] = totals.ranks;
  s["build"] = build_id();
  statistics.write(s);
  // Rank 0's time: the materials' parts of it ("time_split.*" of their statistics; an exchange
  // includes waiting for the slowest rank), the output's, and the MPM's, the rest.
  double mpm = totals.wall_seconds;
  for (const double part : statistics.values_under("time_split."))
    mpm -= part;
  mpm -= output_seconds_;
  s["time_split"]["output"] = output_seconds_;
  s["time_split"]["mpm"] = mpm;
  s["mpm_steps"] = solver.steps();
  s["gravity_stage_steps"] = totals.gravity_stage_steps;
  s["material_points"] = solver.particles().size();
  s["time"] = solver.time();
  s["time_step"] = solver.dt();
  s["dimension"] = D;
  if (!solver.footings().empty())
    s["peak_q"] = peak_bearing_pressure_;  // the history's "q": bearing pressure
  s["largest_stiffened_cfl"] = largest_stiffened_cfl_;
  io::write_json(directory_ + "/summary.json", s);
}

template class Recorder<2>;
template class Recorder<3>;

}  // namespace mpm_lig::mpm
