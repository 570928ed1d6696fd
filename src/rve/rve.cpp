#include "rve/rve.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/plane_strain.h"
#include "dem/file_name.h"
#include "dem/restart_check.h"
#include "rve/engine_input.h"
#include "rve/kinematics.h"
#include "rve/packing.h"
#include "rve/placement.h"

namespace mpm_lig::rve {
namespace {

constexpr const char* kAxes = "xyz";

//! Measure of the engine's cell: area in 2D (what the engine divides its virial by).
double cell_measure(const Mat3& h, int dimension) {
  return dimension == 2 ? h(0, 0) * h(1, 1) : h.determinant();
}

}  // namespace

Rve::Rve(const RveSpec& spec, MPI_Comm comm, const std::string& label)
    : spec_(spec), label_(label), comm_(comm), time_step_(spec.time_step) {
  dem::EngineOptions options;
  options.label = label;
  options.log_file = spec.log_file;
  engine_ = dem::create_engine(spec.engine, comm, options);
}

std::unique_ptr<Rve> Rve::generate(const RveSpec& spec, MPI_Comm comm, const std::string& label) {
  const Packing packing = generate_packing(spec);
  std::unique_ptr<Rve> rve(new Rve(spec, comm, label));
  rve->engine_->commands(setup_input(spec, packing));
  rve->engine_->commands(material_input(spec, spec.contact.friction));
  rve->engine_->commands(dynamics_input(spec, spec.preparation.time_step));
  rve->time_step_ = spec.preparation.time_step;
  rve->engine_->command("run 0");
  return rve;
}

std::unique_ptr<Rve> Rve::read(const RveSpec& spec, const std::string& restart_file, MPI_Comm comm,
                               const std::string& label) {
  // Checked before the engine sees it: LIGGGHTS hangs on an empty file and aborts on a
  // damaged one without a word.
  const std::string problem = dem::restart_file_problem(restart_file, spec.engine, spec.grains);
  if (!problem.empty())
    throw std::runtime_error(label + ": restart file '" + restart_file + "': " + problem);
  std::unique_ptr<Rve> rve(new Rve(spec, comm, label));
  rve->engine_->commands(restart_input(spec, restart_file));
  rve->engine_->commands(material_input(spec, spec.contact.friction));
  rve->engine_->commands(dynamics_input(spec, spec.time_step));
  const long count = rve->engine_->atom_count();
  if (count != spec.grains) {
    throw std::runtime_error(label + ": restart file '" + restart_file + "' holds " +
                             std::to_string(count) + " grains, " + spec.path + ".grains says " +
                             std::to_string(spec.grains));
  }
  return rve;
}

std::unique_ptr<Rve> Rve::from_restart(const RveSpec& spec, const std::string& restart_file,
                                       MPI_Comm comm, const std::string& label) {
  std::unique_ptr<Rve> rve = read(spec, restart_file, comm, label);
  rve->engine_->command("run 0");
  rve->orient_cell();
  return rve;
}

std::unique_ptr<Rve> Rve::from_checkpoint(const RveSpec& spec, const std::string& file,
                                          MPI_Comm comm, const std::string& label) {
  // No `run 0`: the original went on from its state as it was before the write, which the
  // restart file plus the exact placement restore; the next update's run does the set-up.
  Placement exact;
  try {
    exact = read_placement(placement_file(file), spec.grains);
  } catch (const std::exception& e) {
    throw std::runtime_error(label + ": " + e.what());
  }
  std::unique_ptr<Rve> rve = read(spec, file, comm, label);
  put_placement(*rve->engine_, exact);
  return rve;
}

std::string Rve::placement_file(const std::string& checkpoint_file) {
  return checkpoint_file + ".placement";
}

void Rve::orient_cell() {
  if (spec_.cell_angle == 0.0)
    return;
  const double c = std::cos(spec_.cell_angle), s = std::sin(spec_.cell_angle);
  Mat3 turn = Mat3::Identity();
  turn(0, 0) = c;
  turn(0, 1) = -s;
  turn(1, 0) = s;
  turn(1, 1) = c;
  rotation_ = turn * rotation_;
}

Mat3 Rve::box_matrix() const {
  return engine_->box().h();
}

double Rve::volume() const {
  const Mat3 h = box_matrix();
  return spec_.dimension == 2 ? cell_measure(h, 2) * spec_.thickness : h.determinant();
}

Mat3 Rve::stress() {
  const std::vector<double> p = engine_->compute_vector("stress", 6);
  // σ = -P; in 2D the engine's pressure is per unit length (N/m): spread it over the thickness.
  Mat3 sigma_rve = -from_voigt({p[0], p[1], p[2], p[3], p[4], p[5]});
  sigma_rve *= cell_measure(box_matrix(), spec_.dimension) / volume();
  const Mat3 sigma = rotation_ * sigma_rve * rotation_.transpose();
  last_mean_stress_ = mean_pressure(sigma, spec_.dimension);
  return sigma;
}

Observables Rve::observe() {
  Observables o;
  o.stress = stress();
  const GrainState grains = gather_grains(*engine_);
  const std::vector<dem::Contact> contacts = engine_->contacts();
  add_grain_measures(grains, contacts, streaming_, engine_->box().lo, o);
  add_cell_measures(grains, o);
  return o;
}

Observables Rve::observe_health() {
  Observables o;
  o.stress = stress();
  const GrainState grains = gather_grains(*engine_);
  add_health_measures(grains, engine_->overlaps(), streaming_, engine_->box().lo, o);
  add_cell_measures(grains, o);
  return o;
}

void Rve::add_cell_measures(const GrainState& grains, Observables& o) const {
  const double solid = solid_measure(grains.radius, spec_.dimension);
  o.void_ratio = cell_measure(box_matrix(), spec_.dimension) / solid - 1.0;
  o.step_travel = o.max_speed_ratio * time_step_;
}

void Rve::check_blow_up(const Observables& now) const {
  std::ostringstream problem;
  if (now.grains != spec_.grains)
    problem << "lost " << spec_.grains - now.grains << " of " << spec_.grains << " grains";
  else if (!now.stress.allFinite() || !std::isfinite(now.kinetic_energy))
    problem << "stress or velocities are not finite (NaN)";
  else if (now.step_travel > kMaxStepTravel)
    problem << "a grain moves " << now.step_travel << " of its radius per DEM step (limit "
            << kMaxStepTravel << "): numerical blow-up; time step too large?";
  else if (now.max_overlap_ratio > kMaxOverlapRatio)
    problem << "two grains overlap by " << now.max_overlap_ratio << " of the smaller radius (limit "
            << kMaxOverlapRatio
            << "): numerical blow-up or a pressure far beyond the contact law's range";
  if (!problem.str().empty())
    throw std::runtime_error(label_ + ": " + problem.str());
}

void Rve::check_health(const Observables& now) const {
  check_blow_up(now);
  // Both ratios: a liquefied packing has lost its elastic energy but its grains still move at
  // the pace of the imposed flow; only a blow-up outruns both.
  if (now.kinetic_ratio() > spec_.max_kinetic_ratio && now.flow_ratio() > spec_.max_flow_ratio) {
    std::ostringstream problem;
    problem << label_ << ": runaway kinetic energy: kinetic/elastic = " << now.kinetic_ratio()
            << " > " << spec_.path << ".max_kinetic_ratio = " << spec_.max_kinetic_ratio
            << " and kinetic/flow = " << now.flow_ratio() << " > " << spec_.path
            << ".max_flow_ratio = " << spec_.max_flow_ratio
            << " (time step too large or deformation too fast?)";
    throw std::runtime_error(problem.str());
  }
}

void Rve::set_friction(double friction) {
  require_setup();
  engine_->commands(material_input(spec_, friction));
}

void Rve::write_restart(const std::string& file) {
  // A saved packing carries no streaming motion: a clone starts with a resting box.
  set_streaming(Mat3::Zero());
  write_checked_restart(file);
  // A clone re-evaluates the contact forces once when it starts (which advances the tangential
  // history by one step); doing the same here keeps the original bit-identical to its clones.
  engine_->command("run 0");
}

void Rve::write_checked_restart(const std::string& file) {
  // write_restart re-initialises the engine and moves atoms between its ranks: what follows
  // needs a set-up.
  require_setup();
  engine_->command("write_restart " + dem::quoted_file_name(file));
  // The engine's rank 0 writes the file; the others may return before it is closed.
  MPI_Barrier(comm_);
  const std::string problem = dem::restart_file_problem(file, spec_.engine, spec_.grains);
  if (!problem.empty())
    throw std::runtime_error(label_ + ": the restart file '" + file + "' just written: " + problem);
}

void Rve::write_checkpoint(const std::string& file) {
  // write_restart wraps the grains through reduced coordinates (round-off in x and new image
  // flags); the run goes on from the positions it had, and a resume starts from the same.
  const Placement exact = take_placement(*engine_);
  write_checked_restart(file);
  put_placement(*engine_, exact);
  try {
    write_placement(exact, placement_file(file), comm_);
  } catch (const std::exception& e) {
    throw std::runtime_error(label_ + ": " + e.what());
  }
}

void Rve::use_loading_time_step() {
  if (time_step_ == spec_.time_step)
    return;
  engine_->command("timestep " + fmt(spec_.time_step));
  time_step_ = spec_.time_step;
}

void Rve::restore(const State& s) {
  rotation_ = s.rotation;
  streaming_ = s.streaming;
  particle_steps_ = s.particle_steps;
  last_mean_stress_ = s.last_mean_stress;
  strain_ = s.strain;
}

double shear_of_strain(const Mat3& strain, int dimension) {
  const Mat3 in_plane = plane::in_plane(0.5 * (strain + strain.transpose()), dimension);
  const double volumetric = plane::trace_d(in_plane, dimension);
  return plane::engineering_shear(in_plane -
                                  (volumetric / dimension) * plane::identity_d(dimension));
}

int substeps_for_increment(const RveSpec& spec, const Mat3& effective_increment, double mean_stress,
                           double net_shear) {
  const SubstepSpec& s = spec.substeps;
  if (s.fixed > 0)
    return s.fixed;
  const bool sheared = s.sheared_after > 0.0 && net_shear >= s.sheared_after;
  const double inertial_number = sheared ? s.sheared_inertial_number : s.inertial_number;
  // Inertial number I = γ̇ d sqrt(ρ/p), with γ̇ = |ΔF_eff - I| / (n Δt) (docs/DESIGN.md §8).
  const double strain = (effective_increment - Mat3::Identity()).norm();
  const double p = std::max(std::abs(mean_stress), s.pressure_floor);
  const double d = 2.0 * spec.radius.mean();
  const double n = strain * d * std::sqrt(spec.density / p) / (inertial_number * spec.time_step);
  return static_cast<int>(std::min<double>(s.max, std::max<double>(s.min, std::ceil(n))));
}

int predicted_substeps(const RveSpec& spec, const Mat3& dF, double mean_stress, double net_shear) {
  if (spec.substeps.fixed > 0)
    return spec.substeps.fixed;
  // An RVE whose frame is the physical one and whose box is rectangular: the box's own
  // increment is the triangular factor of dF (the rotation taken out).
  return substeps_for_increment(spec, box_step(dF, Mat3::Identity()).target, mean_stress,
                                net_shear);
}

int Rve::substeps_for(const Mat3& effective_increment) {
  return substeps_for_increment(spec_, effective_increment, last_mean_stress_, net_shear());
}

// Streaming velocity: the box's affine velocity field in the grains (docs/DESIGN.md §2.4).
void Rve::set_streaming(const Mat3& gradient) {
  if (!spec_.stream_velocity)
    return;
  const Mat3 change = gradient - streaming_;
  if (change.isZero(0.0))
    return;
  // The engine also takes out the net momentum: grains wrapped across the cell between two
  // changes of the field would otherwise leave an undamped drift of the whole packing.
  engine_->add_velocity_field(change, engine_->box().lo, spec_.dimension);
  streaming_ = gradient;
}

void Rve::reduce_cell_basis() {
  const Mat3 h = box_matrix();
  const Mat3 reduced = reduce_tilts(h);
  if ((reduced - h).norm() <= 1e-12 * h.norm())
    return;
  // Same lattice, other basis: grains are wrapped into the new cell; streaming velocities
  // depend on the cell, so they are taken out first and put back by the next increment.
  // docs/DESIGN.md §2.3.
  set_streaming(Mat3::Zero());
  require_setup();
  std::ostringstream command;
  command << "change_box all xy final " << fmt(reduced(0, 1));
  if (spec_.dimension == 3)
    command << " xz final " << fmt(reduced(0, 2)) << " yz final " << fmt(reduced(1, 2));
  engine_->command(command.str());
}

std::string Rve::deform_fix(const Mat3& target) const {
  const Vec3 lo = engine_->box().lo;
  std::ostringstream fix;
  fix << "fix mpm_deform all deform 1";
  for (int i = 0; i < spec_.dimension; ++i)
    fix << ' ' << kAxes[i] << " final " << fmt(lo[i]) << ' ' << fmt(lo[i] + target(i, i));
  fix << " xy final " << fmt(target(0, 1));
  if (spec_.dimension == 3)
    fix << " xz final " << fmt(target(0, 2)) << " yz final " << fmt(target(1, 2));
  fix << " remap " << (spec_.stream_velocity ? "v" : "x") << " flip no";
  return fix.str();
}

void Rve::require_setup() {
  // The kept fix goes too: a command with its own set-up (change_box, write_restart) must not
  // find a stale target.
  if (deform_fix_kept_)
    engine_->command("unfix mpm_deform");
  deform_fix_kept_ = false;
}

void Rve::run_to_box(const Mat3& target, int steps, EngineRun run) {
  const bool keep = run == EngineRun::continued;
  if (keep && deform_fix_kept_) {
    engine_->run_continued(deform_fix(target), steps);
    return;
  }
  if (!keep)
    require_setup();
  if ((target - box_matrix()).isZero(0.0) && !keep) {
    engine_->command("run " + std::to_string(steps));
    return;
  }
  engine_->command(deform_fix(target));
  // `pre yes` (the default): the fix's target is set in its set-up (docs/DESIGN.md §3.3).
  engine_->command("run " + std::to_string(steps));
  if (keep) {
    deform_fix_kept_ = true;
    return;
  }
  engine_->command("unfix mpm_deform");
}

int Rve::deform(const Mat3& dF, int substeps, EngineRun run) {
  if (spec_.dimension == 2) {
    const double out_of_plane =
        std::abs(dF(0, 2)) + std::abs(dF(1, 2)) + std::abs(dF(2, 0)) + std::abs(dF(2, 1));
    if (out_of_plane > 1e-12 || std::abs(dF(2, 2) - 1.0) > 1e-12)
      throw std::invalid_argument(label_ + ": a 2D RVE takes in-plane deformation increments only");
  }
  // No `run 0` set-up before an update: in LIGGGHTS a set-up re-evaluates the contacts and
  // advances the tangential history by one step, a systematic error per update (measured: the
  // quick-start block's lateral reaction 1.072 p0 H instead of 1.001).
  reduce_cell_basis();
  const Mat3 h = box_matrix();
  const BoxStep step = box_step(rotation_.transpose() * dF * rotation_, h);
  const Mat3 effective = step.target * h.inverse();
  const int n = substeps > 0 ? substeps : substeps_for(effective);
  set_streaming((effective - Mat3::Identity()) / (n * time_step_));
  run_to_box(step.target, n, run);
  rotation_ = rotation_ * step.rotation;
  particle_steps_ += static_cast<double>(n) * static_cast<double>(spec_.grains);
  strain_ += 0.5 * (effective + effective.transpose()) - Mat3::Identity();
  return n;
}

}  // namespace mpm_lig::rve
