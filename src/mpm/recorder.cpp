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

double stepping_efficiency(const materials::SteppingCost& s) {
  return s.makespan > 0.0 ? s.work / (s.groups * s.makespan) : 1.0;
}

materials::MaterialCost total_cost(const MaterialSet& materials) {
  materials::MaterialCost total;
  for (std::size_t m = 0; m < materials.size(); ++m) {
    const materials::MaterialCost c = materials[m]->cost();
    total.simulations += c.simulations;
    total.particle_steps += c.particle_steps;
    total.compute_seconds += c.compute_seconds;
    total.communication_seconds += c.communication_seconds;
    total.preparation_seconds += c.preparation_seconds;
    total.particle_steps_at_max += c.particle_steps_at_max;
    total.particle_steps_low_stress += c.particle_steps_low_stress;
    total.particle_steps_quiet += c.particle_steps_quiet;
    if (c.quiet.enabled) {
      total.quiet.enabled = true;
      total.quiet.predictions += c.quiet.predictions;
      total.quiet.updates += c.quiet.updates;
      total.quiet.checks += c.quiet.checks;
      total.quiet.error_sum += c.quiet.error_sum;
      total.quiet.max_error = std::max(total.quiet.max_error, c.quiet.max_error);
      total.quiet.exceeded += c.quiet.exceeded;
    }
    if (c.continuum_start.enabled) {
      materials::ContinuumStartCost& t = total.continuum_start;
      t.threshold_scale = t.enabled ? std::min(t.threshold_scale, c.continuum_start.threshold_scale)
                                    : c.continuum_start.threshold_scale;
      t.enabled = true;
      t.continuum_updates += c.continuum_start.continuum_updates;
      t.switches += c.continuum_start.switches;
      t.jump_sum += c.continuum_start.jump_sum;
      t.max_jump = std::max(t.max_jump, c.continuum_start.max_jump);
      t.jumps_exceeded += c.continuum_start.jumps_exceeded;
      t.points += static_cast<double>(c.simulations);
    }
    if (c.stepping.enabled) {
      // Materials update one after the other within a step: their works and makespans add.
      materials::SteppingCost& t = total.stepping;
      const materials::SteppingCost& one = c.stepping;
      t.enabled = true;
      t.groups = std::max(t.groups, one.groups);
      t.work_predicted += one.work_predicted;
      t.makespan_predicted += one.makespan_predicted;
      t.work += one.work;
      t.makespan += one.makespan;
      t.bound += one.bound;
      t.seconds += one.seconds;
      t.makespan_seconds += one.makespan_seconds;
      t.migrations += one.migrations;
      t.rebalances += one.rebalances;
      t.migration_seconds += one.migration_seconds;
    }
  }
  return total;
}

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
  last_step_ = solver.steps();
  // The restored packings carry the run's particle-steps so far: the first progress line's DEM
  // rate counts only the steps made after the resume.
  last_particle_steps_ = total_cost(solver.materials()).particle_steps;
}

template <int D>
void Recorder<D>::after_step(const Solver<D>& solver) {
  const auto start = std::chrono::steady_clock::now();
  const long step = solver.steps();
  for (const auto& f : solver.footings())
    peak_bearing_pressure_ = std::max(peak_bearing_pressure_, f.load() / f.contact_area());
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
  const materials::MaterialCost cost = total_cost(solver.materials());
  const double particle_steps = cost.particle_steps;
  if (particle_steps > 0.0) {
    // Summed over all ranks: every rank knows every RVE's step count.
    const double dem_rate = (particle_steps - last_particle_steps_) / std::max(interval, 1e-9);
    std::printf(
        "mpm step %ld/%ld  t = %.6g s  %.3g steps/s  DEM %.3g M particle-steps/s  "
        "stepping efficiency %.3f  ETA %.1f s\n",
        solver.steps(), total_steps_, solver.time(), rate, dem_rate * 1e-6,
        stepping_efficiency(cost.stepping), eta);
  } else {
    std::printf("mpm step %ld/%ld  t = %.6g s  %.0f steps/s  ETA %.1f s\n", solver.steps(),
                total_steps_, solver.time(), rate, eta);
  }
  std::fflush(stdout);
  last_particle_steps_ = particle_steps;
  last_ = std::chrono::steady_clock::now();
  last_step_ = solver.steps();
}

template <int D>
void Recorder<D>::finish(const Solver<D>& solver, const RunTotals& totals) {
  const materials::MaterialCost cost = total_cost(solver.materials());
  nlohmann::json s;
  s["wall_seconds"] = totals.wall_seconds;
  s["ranks"] = totals.ranks;
  s["build"] = build_id();
  s["rve_count"] = cost.simulations;
  s["dem_particle_steps"] = cost.particle_steps;
  // Rank 0's time: the exchange includes waiting for the slowest rank (load imbalance).
  const double mpm = totals.wall_seconds - cost.compute_seconds - cost.communication_seconds -
                     cost.preparation_seconds - output_seconds_;
  s["time_split"] = {{"dem", cost.compute_seconds},
                     {"communication", cost.communication_seconds},
                     {"preparation", cost.preparation_seconds},
                     {"output", output_seconds_},
                     {"mpm", mpm}};
  if (cost.particle_steps > 0.0 && !totals.dem_seconds_per_rank.empty()) {
    // max / mean of the ranks' DEM time: 1 is perfect balance; the excess is waiting.
    const auto& per_rank = totals.dem_seconds_per_rank;
    double sum = 0.0, most = 0.0;
    for (const double t : per_rank) {
      sum += t;
      most = std::max(most, t);
    }
    s["dem_seconds_per_rank"] = per_rank;
    // Of whole-run times: blind to the waiting of each step, which "stepping" shows.
    s["load_imbalance"] = sum > 0.0 ? most * static_cast<double>(per_rank.size()) / sum : 1.0;
  }
  if (cost.stepping.enabled && cost.particle_steps > 0.0) {
    const materials::SteppingCost& t = cost.stepping;
    const auto efficiency = [&](double work, double makespan) {
      return makespan > 0.0 ? work / (t.groups * makespan) : 1.0;
    };
    // The mean group's waiting for the busiest one, step by step (from the owners' times).
    const double waiting = t.makespan_seconds - t.seconds / t.groups;
    s["stepping"] = {
        {"rank_groups", t.groups},
        {"efficiency", stepping_efficiency(t)},
        {"efficiency_predicted", efficiency(t.work_predicted, t.makespan_predicted)},
        {"efficiency_seconds", efficiency(t.seconds, t.makespan_seconds)},
        {"efficiency_bound", efficiency(t.work, t.bound)},
        {"waiting_seconds", waiting},
        {"waiting_share", totals.wall_seconds > 0.0 ? waiting / totals.wall_seconds : 0.0},
        {"migrations", t.migrations},
        {"rebalances", t.rebalances},
        {"migration_seconds", t.migration_seconds}};
  }
  if (cost.particle_steps > 0.0)
    s["dem_work_shares"] = {
        {"at_substeps_max", cost.particle_steps_at_max / cost.particle_steps},
        {"mean_stress_below_10_percent_of_preparation",
         cost.particle_steps_low_stress / cost.particle_steps},
        {"strain_per_step_below_1e-5", cost.particle_steps_quiet / cost.particle_steps}};
  if (cost.quiet.enabled) {
    const materials::PredictionCost& q = cost.quiet;
    s["quiet_points"] = {
        {"predicted_updates", q.predictions},
        {"dem_updates", q.updates},
        {"predicted_share",
         q.predictions + q.updates > 0.0 ? q.predictions / (q.predictions + q.updates) : 0.0},
        {"checks", q.checks},
        {"mean_error", q.checks > 0.0 ? q.error_sum / q.checks : 0.0},
        {"max_error", q.max_error},
        {"checks_above_max_error", q.exceeded}};
  }
  if (cost.continuum_start.enabled) {
    const materials::ContinuumStartCost& c = cost.continuum_start;
    s["start_as_continuum"] = {{"continuum_updates", c.continuum_updates},
                               {"switched_points", c.switches},
                               {"continuum_points", c.points - c.switches},
                               {"mean_jump", c.switches > 0.0 ? c.jump_sum / c.switches : 0.0},
                               {"max_jump", c.max_jump},
                               {"jumps_above_max_jump", c.jumps_exceeded},
                               {"threshold_scale", c.threshold_scale}};
  }
  s["mpm_steps"] = solver.steps();
  s["gravity_stage_steps"] = totals.gravity_stage_steps;
  s["material_points"] = solver.particles().size();
  s["time"] = solver.time();
  s["time_step"] = solver.dt();
  s["dimension"] = D;
  if (!solver.footings().empty())
    s["peak_q"] = peak_bearing_pressure_;  // the history's "q": bearing pressure
  io::write_json(directory_ + "/summary.json", s);
}

template class Recorder<2>;
template class Recorder<3>;

}  // namespace mpm_lig::mpm
