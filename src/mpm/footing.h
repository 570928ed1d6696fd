#pragma once

#include <array>
#include <vector>

#include <Eigen/Dense>

#include "mpm/case_spec.h"
#include "mpm/grid.h"
#include "mpm/particles.h"

namespace mpm_lig::mpm {

//! Along one horizontal axis: the footprint [center - width/2, center + width/2] clipped to
//! the mesh [origin, origin + size], and the span the penalty contact presses, the clipped
//! footprint less `inset` at each edge inside the mesh. An edge on a mesh face (a half
//! model's symmetry plane) is no edge: nothing leaves through it, so the pressed span's end
//! lies at infinity there.
struct FootingSpan {
  double lo, hi;                  // the clipped footprint
  double pressed_lo, pressed_hi;  // the pressed span (+-infinity at a mesh face)
  //! Whether the pressed span holds any of the mesh (within `tol`).
  bool presses(double tol) const {
    return std::min(pressed_hi, hi) - std::max(pressed_lo, lo) > tol;
  }
};
FootingSpan footing_span(double center, double width, double origin, double size, double inset,
                         double tol);

//! A rigid footing pushed down the last axis at a prescribed speed.
//!
//! It acts through one of two contacts (the case's `contact`). `penalty` (`press`): every
//! point whose box overlaps the footing (its footprint less half a cell at each edge inside
//! the mesh, by default) is pushed out through the nearest face with a force proportional to
//! the overlap, and a rough base holds each point it touches by a spring from where that
//! point first touched it; the load is the sum of those forces, a function of positions
//! alone, so it does not depend on the time step (docs/footing_contact.md).
//! `nodes` (`apply`) acts on the grid: nodes inside its footprint at or above its base take
//! its velocity when the material there pushes against it (unilateral contact: the soil may
//! move away, never pull). The base moves continuously through the fixed grid, so the node row just
//! below it is blended in with weight 1 - (base - y)/h: without this the load jumps every
//! time the base crosses a node row. Likewise across the edges: a node takes the share of
//! its tributary width [x - h/2, x + h/2] that lies under the footing (1/2 at an edge on a
//! grid line), else the footing acts as if it were about one cell wider. Rough: the
//! horizontal velocity is the footing's too; smooth: only the normal one is imposed.
template <int D>
class RigidFooting {
 public:
  using Vec = Eigen::Matrix<double, D, 1>;

  RigidFooting(const Footing& spec, const Grid<D>& grid);

  //! Whether it acts by the penalty contact (`press`), else by holding nodes (`apply`).
  bool presses() const { return spec_.contact == Footing::Contact::penalty; }
  //! Penalty contact: add the footing's force on each point it overlaps to
  //! `particles.external_force` and store the load. `modulus` [Pa] sets the stiffness.
  void press(Particles<D>& particles, const Vec& cell, double modulus);
  //! Node contact: impose the footing on `grid.velocity_new`; with `record`, store its
  //! reaction.
  void apply(Grid<D>& grid, double t, double scale, double dt, bool record);
  //! Move the base by one step.
  void advance(double t, double scale, double dt);
  //! Whether the case asked for `keep_points_out`.
  bool keeps_points_out() const { return spec_.keep_points_out; }
  //! A point whose centre lies inside the footing once its base has moved this step (within
  //! the footprint, above the base) goes back onto the nearest face, and its velocity loses
  //! the component into that face. The grid contact alone lets the base overtake points at
  //! its edge; carried inside and released later, they jolt the load (docs/
  //! footing_mesh_convergence.md).
  void push_out(Vec& x, Vec& v, double t, double scale, double dt) const;

  //! Downward velocity at time t [m/s].
  double speed(double t, double scale) const {
    return scale * spec_.velocity * spec_.function.at(t);
  }
  double settlement() const { return settlement_; }
  double base() const { return spec_.base - settlement_; }
  //! Force the footing exerts on the material along -last axis (positive pushing) [N,
  //! per unit thickness in 2D], from the part of the footing inside the mesh.
  double load() const { return load_; }
  //! Horizontal reaction force (rough footings) [N].
  const Vec& reaction() const { return reaction_; }
  //! For a resumed run: the state after a checkpointed step.
  void restore(double settlement, double load, const Vec& reaction) {
    settlement_ = settlement;
    load_ = load;
    reaction_ = reaction;
  }
  //! Penalty contact, rough base: per point, where it first touched the base (NaN in the
  //! first component while it does not touch); empty before the first `press`.
  const std::vector<Vec>& anchors() const { return anchors_; }
  void restore_anchors(std::vector<Vec> anchors) { anchors_ = std::move(anchors); }
  //! Footprint area inside the mesh (its width in 2D) [m^(D-1)].
  double contact_area() const { return area_; }

 private:
  Footing spec_;
  std::vector<long> footprint_;  // nodes whose tributary width reaches under the footing
  std::vector<double> share_;    // the share of it under the footing
  double area_ = 1.0;
  double settlement_ = 0.0;
  double load_ = 0.0;
  Vec reaction_ = Vec::Zero();
  std::vector<Vec> anchors_;
  // The span the penalty contact presses along each horizontal axis: the footprint, less
  // half a cell at each edge inside the mesh with `penalty_edge_inset`.
  std::array<double, D> pressed_lo_{}, pressed_hi_{};

  void slide_past_friction_limit(Vec& f, const Vec& x, Vec& anchor) const;
};

}  // namespace mpm_lig::mpm
