#include "mpm/constraints.h"

#include <algorithm>
#include <array>

namespace mpm_lig::mpm {

template <int D>
std::vector<long> select_nodes(const NodeSelector& selector, const Grid<D>& grid) {
  std::vector<long> out;
  for (long id = 0; id < static_cast<long>(grid.node_count()); ++id) {
    const auto index = grid.node_index(id);
    if (selector.by_face) {
      const long want = selector.upper ? grid.cells(selector.axis) : 0;
      if (index[selector.axis] == want)
        out.push_back(id);
      continue;
    }
    const auto x = grid.node_position(id);
    if (selector.box.contains(x.data(), D, 1e-9 * grid.min_cell()))
      out.push_back(id);
  }
  return out;
}

namespace {

//! The node that carries node `id`'s mass: its lower-face partner on an upper face of a
//! periodic axis, itself otherwise.
template <int D>
long periodic_partner(long id, const Grid<D>& grid) {
  const auto index = grid.node_index(id);
  std::array<long, D> folded{};
  for (int d = 0; d < D; ++d)
    folded[d] = grid.wrap(index[d], d);
  return grid.node_id(folded);
}

//! Replace upper-face nodes of periodic axes by their lower-face partners, without repeats.
template <int D>
std::vector<long> fold_periodic(const std::vector<long>& nodes, const Grid<D>& grid) {
  std::vector<long> out;
  for (const long id : nodes) {
    const long partner = periodic_partner(id, grid);
    if (std::find(out.begin(), out.end(), partner) == out.end())
      out.push_back(partner);
  }
  return out;
}

//! ω × (x − center), in the first D components.
template <int D>
Eigen::Matrix<double, D, 1> rigid_rotation_velocity(const Constraint& c,
                                                    const Eigen::Matrix<double, D, 1>& x) {
  Vec3 arm = Vec3::Zero();
  for (int d = 0; d < D; ++d)
    arm[d] = x[d] - c.center[d];
  return c.angular_velocity.cross(arm).template head<D>();
}

}  // namespace

template <int D>
NodeConstraints<D>::NodeConstraints(const std::vector<Constraint>& constraints,
                                    const Grid<D>& grid) {
  for (const Constraint& c : constraints)
    sets_.push_back({c, fold_periodic(select_nodes(c.nodes, grid), grid)});
  reactions_.assign(sets_.size(), Vec::Zero());
}

template <int D>
bool NodeConstraints<D>::prescribes_every_node(const Grid<D>& grid) const {
  std::vector<std::array<bool, D>> held(grid.node_count(), std::array<bool, D>{});
  for (const Set& s : sets_) {
    const bool all =
        s.spec.type == Constraint::Type::fixed || s.spec.type == Constraint::Type::rotation;
    for (const long node : s.nodes)
      for (int d = 0; d < D; ++d)
        held[node][d] = held[node][d] || all || d == s.spec.direction;
  }
  for (std::size_t id = 0; id < held.size(); ++id) {
    if (periodic_partner(static_cast<long>(id), grid) != static_cast<long>(id))
      continue;  // its partner's constraints are the ones that act
    for (int d = 0; d < D; ++d)
      if (!held[id][d])
        return false;
  }
  return true;
}

template <int D>
void NodeConstraints<D>::apply(Grid<D>& grid, double t, double scale, double dt, bool record) {
  for (std::size_t k = 0; k < sets_.size(); ++k) {
    const Constraint& c = sets_[k].spec;
    Vec reaction = Vec::Zero();
    for (const long node : sets_[k].nodes) {
      const double m = grid.mass[node];
      if (m <= 0.0)
        continue;
      Vec& v = grid.velocity_new[node];
      const Vec trial = v;
      Vec held = Vec::Zero();  // 1 on the components this constraint imposes
      switch (c.type) {
        case Constraint::Type::fixed:
          v.setZero();
          held.setOnes();
          break;
        case Constraint::Type::roller:
          v[c.direction] = 0.0;
          held[c.direction] = 1.0;
          break;
        case Constraint::Type::velocity:
          v[c.direction] = scale * c.velocity * c.function.at(t);
          held[c.direction] = 1.0;
          break;
        case Constraint::Type::rotation:
          v = scale * c.function.at(t) * rigid_rotation_velocity(c, grid.node_position(node));
          held.setOnes();
          break;
      }
      // The impulse that imposes v, plus the damping force on the imposed components:
      // the constraint, not the (fictitious) damping, holds the node.
      reaction += m * (v - trial) / dt + held.cwiseProduct(grid.damping[node]);
    }
    if (record)
      reactions_[k] = reaction;
  }
}

template class NodeConstraints<2>;
template class NodeConstraints<3>;
template std::vector<long> select_nodes<2>(const NodeSelector&, const Grid<2>&);
template std::vector<long> select_nodes<3>(const NodeSelector&, const Grid<3>&);

}  // namespace mpm_lig::mpm
