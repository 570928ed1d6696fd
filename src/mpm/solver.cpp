#include "mpm/solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/case_error.h"

namespace mpm_lig::mpm {
namespace {

//! Nodal masses below this fraction of the smallest point mass count as empty nodes.
constexpr double kEmptyNodeFraction = 1e-10;

template <class V>
std::string describe_position(const V& x) {
  std::ostringstream s;
  s << "(";
  for (int d = 0; d < x.size(); ++d)
    s << (d ? ", " : "") << x[d];
  s << ")";
  return s.str();
}

//! Why a point's deformation increment cannot go to its material ("" when it can).
std::string increment_problem(const Mat3& dF) {
  if (!dF.allFinite())
    return "is not finite; the MPM state has overflowed (time step too large for the loading, "
           "or a prescribed value out of range?)";
  const double det = dF.determinant();
  if (!(det > 0.0)) {
    std::ostringstream s;
    s << "inverts the point (det dF = " << det
      << "): it moved through a neighbour within one step (time step too large for the "
         "loading, or a point crossing a fixed boundary?)";
    return s.str();
  }
  return "";
}

//! A solver steps prepared materials only: a DEM material has no packings before prepare().
MaterialSet require_prepared(MaterialSet materials) {
  if (!materials.prepared())
    throw std::logic_error("Solver: the materials are not prepared (MaterialSet::prepare)");
  return materials;
}

//! The deformation increment of one step from its velocity gradient times the step,
//! ΔF = (I − ΔtL/2)⁻¹ (I + ΔtL/2) (midpoint rule, second order). Unlike I + ΔtL it is an exact
//! rotation when L is a spin: a body turned rigidly keeps its volume and its stress, however
//! far it turns (I + ΔtL stretches it by 1 + (ωΔt)² each step).
template <int D>
Mat3 step_increment(const Eigen::Matrix<double, D, D>& gradient_step) {
  using Matrix = Eigen::Matrix<double, D, D>;
  const Matrix half = 0.5 * gradient_step;
  Mat3 dF = Mat3::Identity();
  dF.template topLeftCorner<D, D>() =
      (Matrix::Identity() - half).partialPivLu().solve(Matrix::Identity() + half);
  return dF;
}

}  // namespace

template <int D>
Solver<D>::Solver(const MpmCase& c, MaterialSet materials)
    : materials_(require_prepared(std::move(materials))),
      grid_(
          Eigen::Map<const Vec>(c.origin.data()), Eigen::Map<const Vec>(c.size.data()),
          [&] {
            std::array<int, D> cells{};
            std::copy(c.cells.begin(), c.cells.end(), cells.begin());
            return cells;
          }(),
          [&] {
            std::array<bool, D> periodic{};
            std::copy_n(c.periodic.begin(), std::min<std::size_t>(D, c.periodic.size()),
                        periodic.begin());
            return periodic;
          }()),
      particles_(generate_particles<D>(c, materials_)),
      shape_(shape_registry().create(c.shape_function)),
      constraints_(c.constraints, grid_),
      kinematics_(kinematics_operators<D>(c)),
      second_gradient_(c.has_second_gradient() ? std::make_unique<SecondGradient<D>>(
                                                     c.internal_length, c.softening_modulus,
                                                     c.gradient_yield_strain / c.internal_length,
                                                     c.gradient_residual_weight)
                                               : nullptr),
      tractions_(c.tractions),
      gravity_(Eigen::Map<const Vec>(c.gravity.data())),
      musl_(c.musl),
      flip_(c.flip),
      damping_(c.damping),
      case_damping_(c.damping),
      record_damping_work_(c.record_damping_work),
      mass_scaling_(c.mass_scaling) {
  for (const Footing& f : c.footings)
    footings_.emplace_back(f, grid_);
  for (std::size_t m = 0; m < materials_.size(); ++m)
    contact_modulus_ = std::max(contact_modulus_, materials_[m]->wave_modulus());
  traction_points_.resize(tractions_.size());
  for (std::size_t k = 0; k < tractions_.size(); ++k) {
    for (std::size_t p = 0; p < particles_.size(); ++p) {
      if (tractions_[k].points.contains(particles_.position[p].data(), D, 0.0))
        traction_points_[k].push_back(p);
    }
  }
  const std::size_t nm = materials_.size();
  batch_particles_.resize(nm);
  batch_points_.resize(nm);
  batch_increments_.resize(nm);
  batch_stress_.resize(nm);
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    batch_particles_[particles_.material[p]].push_back(p);
    batch_points_[particles_.material[p]].push_back(particles_.material_point[p]);
  }
  for (std::size_t m = 0; m < nm; ++m) {
    batch_increments_[m].resize(batch_points_[m].size());
    batch_stress_[m].resize(batch_points_[m].size());
  }
  weights_.resize(particles_.size());
  increments_.resize(particles_.size());
  // The second-gradient energy stiffens a wave of number k by D sin²(kh)/h² (its fitted
  // gradient is sin(kh)/h times the wave's, docs/methods.md §7), at most D/h²: D (π/h)² =
  // G_s (ℓ/h)², the stiffening of the continuum's shortest wave, bounds it.
  // The fit's residual energy (β > 0) stiffens a strain alternating between neighbouring
  // points, a spacing s = h / (points per cell) apart, by at most about 4 β D / s²: added.
  if (second_gradient_) {
    gradient_modulus_ = c.softening_modulus * (c.internal_length / grid_.min_cell()) *
                        (c.internal_length / grid_.min_cell());
    if (c.gradient_residual_weight > 0.0) {
      int points_per_cell = 1;
      for (const auto& body : c.bodies)
        points_per_cell = std::max(points_per_cell, body.points_per_cell);
      const double spacing = grid_.min_cell() / points_per_cell;
      gradient_modulus_ +=
          4.0 * c.gradient_residual_weight * second_gradient_->modulus() / (spacing * spacing);
    }
  }
  if (c.fixed_time_step)
    check_fixed_time_step(c);
  dt_ = c.fixed_time_step ? c.time_step : stable_time_step(c.cfl);
}

template <int D>
void Solver<D>::check_fixed_time_step(const MpmCase& c) const {
  const double limit = stable_time_step(1.0);
  if (c.time_step <= limit || constraints_.prescribes_every_node(grid_))
    return;
  std::ostringstream text;
  text << c.time_step << " s is above the stable time step " << limit
       << " s (the cell over the fastest wave speed, CFL 1"
       << (second_gradient_ ? ", the waves stiffened by the internal length's second gradient" : "")
       << "): the explicit update would be unstable; give a smaller step or \"cfl\"";
  throw CaseError("analysis.time_step.fixed", text.str());
}

template <int D>
double Solver<D>::wave_speed(bool now) const {
  double speed = 0.0;
  for (std::size_t k = 0; k < materials_.size(); ++k) {
    const materials::Material& m = *materials_[k];
    const double modulus = now ? m.current_wave_modulus() : m.wave_modulus();
    speed =
        std::max(speed, std::sqrt((modulus + gradient_modulus_) / (m.density() * mass_scaling_)));
  }
  return speed;
}

template <int D>
double Solver<D>::stable_time_step(double cfl) const {
  return cfl * grid_.min_cell() / wave_speed(false);
}

template <int D>
double Solver<D>::stiffened_cfl() const {
  return dt_ * wave_speed(true) / grid_.min_cell();
}

template <int D>
void Solver<D>::set_gravity_stage(bool on, double damping) {
  prescribed_scale_ = on ? 0.0 : 1.0;
  damping_ = on ? damping : case_damping_;
}

template <int D>
void Solver<D>::begin_main_stage() {
  set_gravity_stage(false, 0.0);
  time_ = 0.0;
  steps_ = 0;
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    particles_.velocity[p].setZero();
    particles_.reference[p] = particles_.position[p];
  }
  if (second_gradient_)
    second_gradient_->forget_relaxation();
  damping_work_ = 0.0;
}

template <int D>
void Solver<D>::step() {
  compute_shape_functions();
  if (second_gradient_)
    compute_gradient_forces();
  compute_external_forces();
  map_particles_to_grid();
  update_grid();
  map_grid_to_particles();
  if (musl_)
    remap_momentum();
  compute_deformation();
  apply_kinematics();
  accumulate_deformation();
  if (second_gradient_)
    second_gradient_->relax(particles_, grid_);
  update_stress();
  for (auto& f : footings_)
    f.advance(time_, prescribed_scale_, dt_);
  time_ += dt_;
  ++steps_;
}

template <int D>
void Solver<D>::compute_shape_functions() {
  const Vec& origin = grid_.origin();
  const Vec& cell = grid_.cell();
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const Vec& x = particles_.position[p];
    const Vec xi = (x - origin).cwiseQuotient(cell);
    for (int d = 0; d < D; ++d) {
      if (!(xi[d] >= 0.0 && xi[d] <= grid_.cells(d))) {
        throw ReplicatedError("material point " + std::to_string(p) + " left the mesh at " +
                              describe_position(x));
      }
    }
    std::array<Weights1d, D> w;
    for (int d = 0; d < D; ++d)
      w[d] = shape_->weights(xi[d], particles_.half_length[p][d], cell[d]);
    PointWeights<D>& pw = weights_[p];
    pw.count = 0;
    std::array<int, D> k{};
    while (true) {
      std::array<long, D> index;
      double value = 1.0;
      Vec gradient = Vec::Ones();
      for (int d = 0; d < D; ++d) {
        // A GIMP point at a grid face reaches past it: the weight of the missing node goes
        // to the face node, which keeps the partition of unity (and of its gradient).
        // Along a periodic axis the node index wraps instead: the upper face is the lower one.
        const long i = w[d].first + k[d];
        index[d] = grid_.periodic(d) ? grid_.wrap(i, d) : std::clamp<long>(i, 0, grid_.cells(d));
        value *= w[d].value[k[d]];
        for (int e = 0; e < D; ++e)
          gradient[e] *= e == d ? w[d].gradient[k[d]] : w[d].value[k[d]];
      }
      pw.node[pw.count] = grid_.node_id(index);
      pw.value[pw.count] = value;
      pw.gradient[pw.count] = gradient;
      ++pw.count;
      int d = 0;
      while (d < D && ++k[d] == w[d].count)
        k[d++] = 0;
      if (d == D)
        break;
    }
  }
}

template <int D>
void Solver<D>::compute_gradient_forces() {
  second_gradient_->force_tensors(particles_, grid_, gradient_forces_);
  // The operators will rewrite the rates these tensors do work on: their work-conjugate keeps
  // the forces' power equal to the energy's change (volumetric smoothing's cell-mean volume).
  const KinematicsContext<D> context{particles_, grid_, dt_};
  for (auto op = kinematics_.rbegin(); op != kinematics_.rend(); ++op)
    (*op)->pull_back(context, gradient_forces_);
}

template <int D>
void Solver<D>::wrap_periodic(Vec& x) const {
  for (int d = 0; d < D; ++d) {
    if (!grid_.periodic(d))
      continue;
    const double length = grid_.size()[d];
    const double offset = x[d] - grid_.origin()[d];
    if (offset < 0.0 || offset >= length)
      x[d] = grid_.origin()[d] + (offset - length * std::floor(offset / length));
  }
}

template <int D>
void Solver<D>::compute_external_forces() {
  for (auto& f : particles_.external_force)
    f.setZero();
  for (std::size_t k = 0; k < tractions_.size(); ++k) {
    const Vec t =
        Eigen::Map<const Vec>(tractions_[k].traction.data()) * tractions_[k].function.at(time_);
    for (const std::size_t p : traction_points_[k]) {
      const double area = std::pow(particles_.volume0[p], (D - 1.0) / D);
      particles_.external_force[p] += area * t;
    }
  }
  for (auto& f : footings_) {
    if (f.presses())
      f.press(particles_, grid_.cell(), contact_modulus_);
  }
}

template <int D>
void Solver<D>::map_particles_to_grid() {
  grid_.reset();
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const double m = particles_.mass[p];
    const double inertia = mass_scaling_ * m;
    const Vec momentum = inertia * particles_.velocity[p];
    const Vec body_force = m * gravity_ + particles_.external_force[p];
    Eigen::Matrix<double, D, D> vs =
        particles_.volume[p] * particles_.stress[p].template topLeftCorner<D, D>();
    if (second_gradient_)
      vs += gradient_forces_[p];
    const PointWeights<D>& w = weights_[p];
    for (int a = 0; a < w.count; ++a) {
      const long i = w.node[a];
      const double n = w.value[a];
      grid_.mass[i] += n * inertia;
      grid_.momentum[i] += n * momentum;
      grid_.force[i] += n * body_force - vs * w.gradient[a];
    }
  }
}

template <int D>
void Solver<D>::update_grid() {
  double min_mass = std::numeric_limits<double>::max();
  for (const double m : particles_.mass)
    min_mass = std::min(min_mass, m * mass_scaling_);
  const double empty = kEmptyNodeFraction * min_mass;
  for (std::size_t i = 0; i < grid_.node_count(); ++i) {
    const double m = grid_.mass[i];
    if (m <= empty) {
      grid_.mass[i] = 0.0;
      grid_.velocity[i].setZero();
      grid_.velocity_new[i].setZero();
      grid_.damping[i].setZero();
      continue;
    }
    const Vec v = grid_.momentum[i] / m;
    Vec f = grid_.force[i];
    // Local non-viscous damping: a force opposing the motion, proportional to the
    // unbalanced force, so it vanishes at equilibrium and does not depend on the mass.
    for (int d = 0; d < D && damping_ > 0.0; ++d) {
      if (v[d] != 0.0)
        f[d] -= damping_ * std::abs(f[d]) * (v[d] > 0.0 ? 1.0 : -1.0);
    }
    grid_.damping[i] = f - grid_.force[i];
    grid_.velocity[i] = v;
    grid_.velocity_new[i] = v + f * (dt_ / m);
  }
  const bool record = record_damping_work_ && damping_ != 0.0;
  if (record)
    trial_velocity_ = grid_.velocity_new;
  apply_boundary_conditions(true);
  if (record)
    add_damping_work();
}

template <int D>
void Solver<D>::add_damping_work() {
  // The damping force over the step, at the velocity the points move with; a component that a
  // constraint or a footing imposes is held by its reaction (which takes the damping force),
  // so the damping does no work there.
  for (std::size_t i = 0; i < grid_.node_count(); ++i) {
    for (int d = 0; d < D; ++d) {
      if (grid_.velocity_new[i][d] == trial_velocity_[i][d])
        damping_work_ -= grid_.damping[i][d] * grid_.velocity_new[i][d] * dt_;
    }
  }
}

template <int D>
void Solver<D>::apply_boundary_conditions(bool record) {
  for (auto& f : footings_) {
    if (!f.presses())
      f.apply(grid_, time_, prescribed_scale_, dt_, record);
  }
  constraints_.apply(grid_, time_, prescribed_scale_, dt_, record);
}

template <int D>
void Solver<D>::map_grid_to_particles() {
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const PointWeights<D>& w = weights_[p];
    Vec v_pic = Vec::Zero();
    Vec dv = Vec::Zero();
    for (int a = 0; a < w.count; ++a) {
      const long i = w.node[a];
      v_pic += w.value[a] * grid_.velocity_new[i];
      dv += w.value[a] * (grid_.velocity_new[i] - grid_.velocity[i]);
    }
    Vec& v = particles_.velocity[p];
    v = flip_ * (v + dv) + (1.0 - flip_) * v_pic;
    particles_.position[p] += dt_ * v_pic;
    wrap_periodic(particles_.position[p]);
    for (const auto& f : footings_) {
      if (f.keeps_points_out())
        f.push_out(particles_.position[p], v, time_, prescribed_scale_, dt_);
    }
  }
}

template <int D>
void Solver<D>::remap_momentum() {
  std::fill(grid_.momentum.begin(), grid_.momentum.end(), Vec::Zero());
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const Vec momentum = mass_scaling_ * particles_.mass[p] * particles_.velocity[p];
    const PointWeights<D>& w = weights_[p];
    for (int a = 0; a < w.count; ++a)
      grid_.momentum[w.node[a]] += w.value[a] * momentum;
  }
  for (std::size_t i = 0; i < grid_.node_count(); ++i) {
    if (grid_.mass[i] > 0.0)
      grid_.velocity_new[i] = grid_.momentum[i] / grid_.mass[i];
  }
  apply_boundary_conditions(false);
}

template <int D>
void Solver<D>::compute_deformation() {
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const PointWeights<D>& w = weights_[p];
    Eigen::Matrix<double, D, D> L = Eigen::Matrix<double, D, D>::Zero();
    for (int a = 0; a < w.count; ++a)
      L.noalias() += grid_.velocity_new[w.node[a]] * w.gradient[a].transpose();
    increments_[p] = step_increment<D>(dt_ * L);
  }
}

template <int D>
void Solver<D>::apply_kinematics() {
  const KinematicsContext<D> context{particles_, grid_, dt_};
  for (const auto& op : kinematics_)
    op->apply(context, increments_);
}

template <int D>
void Solver<D>::accumulate_deformation() {
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    particles_.deformation[p] = increments_[p] * particles_.deformation[p];
    particles_.volume[p] *= increments_[p].determinant();
  }
}

template <int D>
void Solver<D>::update_stress() {
  for (std::size_t m = 0; m < materials_.size(); ++m) {
    const auto& points = batch_particles_[m];
    for (std::size_t k = 0; k < points.size(); ++k) {
      batch_increments_[m][k] = increments_[points[k]];
      // A material (a DEM engine above all) must never be handed NaN, infinity or an
      // inverted point: it would fail later, and be blamed, for a problem of the MPM's.
      const std::string problem = increment_problem(batch_increments_[m][k]);
      if (!problem.empty())
        throw ReplicatedError("step " + std::to_string(steps_ + 1) +
                              ": the deformation increment of material " + "point " +
                              std::to_string(points[k]) + " at " +
                              describe_position(particles_.position[points[k]]) + " (materials[" +
                              std::to_string(m) + "]) " + problem);
    }
    materials_[m]->update({batch_points_[m], batch_increments_[m], dt_}, batch_stress_[m]);
    for (std::size_t k = 0; k < points.size(); ++k)
      particles_.stress[points[k]] = batch_stress_[m][k];
  }
}

template <int D>
double Solver<D>::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p)
    e += 0.5 * particles_.mass[p] * particles_.velocity[p].squaredNorm();
  return e;
}

template <int D>
double Solver<D>::gradient_energy() const {
  return second_gradient_ ? second_gradient_->energy(particles_, grid_) : 0.0;
}

template <int D>
double Solver<D>::gradient_dissipation() const {
  return second_gradient_ ? second_gradient_->dissipated() : 0.0;
}

template <int D>
double Solver<D>::total_mass() const {
  double m = 0.0;
  for (const double mp : particles_.mass)
    m += mp;
  return m;
}

template <int D>
typename Solver<D>::Vec Solver<D>::total_momentum() const {
  Vec p = Vec::Zero();
  for (std::size_t k = 0; k < particles_.size(); ++k)
    p += particles_.mass[k] * particles_.velocity[k];
  return p;
}

template class Solver<2>;
template class Solver<3>;

}  // namespace mpm_lig::mpm
