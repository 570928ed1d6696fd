#pragma once

#include <vector>

#include <Eigen/Dense>

#include "mpm/case_spec.h"
#include "mpm/grid.h"

namespace mpm_lig::mpm {

//! The node-set constraints of a case (fixed, roller, prescribed velocity), resolved to
//! node lists once, applied to the nodal velocities every step; the force each constraint
//! needs (its reaction on the material) is summed per constraint.
template <int D>
class NodeConstraints {
 public:
  using Vec = Eigen::Matrix<double, D, 1>;

  //! Along a periodic axis of `grid` the upper face is the lower one: a set naming an
  //! upper-face node acts on its lower-face partner (the node that carries the mass).
  NodeConstraints(const std::vector<Constraint>& constraints, const Grid<D>& grid);

  //! Impose the constraints on `grid.velocity_new` at time `t`; prescribed velocities are
  //! scaled by `scale` (0 freezes them, in the gravity stage). With `record`, store the
  //! reaction of each constraint: sum over its nodes of m (v_imposed - v_trial) / dt.
  void apply(Grid<D>& grid, double t, double scale, double dt, bool record);

  std::size_t count() const { return sets_.size(); }
  //! Whether every velocity component of every node of `grid` is imposed (a fully prescribed
  //! motion, which leaves no dynamics to be unstable); an upper periodic face counts as its
  //! lower partner.
  bool prescribes_every_node(const Grid<D>& grid) const;
  //! Reaction force of constraint k from the last recorded application [N].
  const Vec& reaction(std::size_t k) const { return reactions_[k]; }
  //! Nodes of constraint k (for tests and diagnostics).
  const std::vector<long>& nodes(std::size_t k) const { return sets_[k].nodes; }

 private:
  struct Set {
    Constraint spec;
    std::vector<long> nodes;
  };
  std::vector<Set> sets_;
  std::vector<Vec> reactions_;
};

//! Which grid nodes a selector picks.
template <int D>
std::vector<long> select_nodes(const NodeSelector& selector, const Grid<D>& grid);

}  // namespace mpm_lig::mpm
