#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Dense>

namespace mpm_lig::mpm {

//! Structured background grid: `cells[d]` cells of size `cell[d]` from `origin` along each
//! axis, nodes numbered with x fastest. Holds the nodal fields the step rebuilds every time.
//! Along a periodic axis the grid wraps around: node index cells[d] is node 0 again, so the
//! upper-face nodes never carry mass.
template <int D>
class Grid {
 public:
  using Vec = Eigen::Matrix<double, D, 1>;
  using Index = Eigen::Matrix<long, D, 1>;

  Grid(const Vec& origin, const Vec& size, const std::array<int, D>& cells,
       const std::array<bool, D>& periodic = {});

  const Vec& origin() const { return origin_; }
  const Vec& cell() const { return cell_; }
  const Vec& size() const { return size_; }
  int cells(int d) const { return cells_[d]; }
  //! Nodes along axis d (cells + 1).
  long nodes(int d) const { return cells_[d] + 1; }
  std::size_t node_count() const { return mass.size(); }
  //! Node number of a node index triple; -1 when outside the grid.
  long node_id(const std::array<long, D>& index) const;
  Index node_index(long id) const;
  Vec node_position(long id) const;
  bool periodic(int d) const { return periodic_[d]; }
  //! A node index along axis d as the grid sees it: modulo cells[d] on a periodic axis.
  long wrap(long i, int d) const {
    return periodic_[d] ? ((i % cells_[d]) + cells_[d]) % cells_[d] : i;
  }
  //! Smallest cell size: sets the CFL time step.
  double min_cell() const { return cell_.minCoeff(); }

  //! Zero every nodal field before a mapping.
  void reset();

  std::vector<double> mass;       //!< inertial mass (mass scaling included) [kg]
  std::vector<Vec> momentum;      //!< [kg m/s]
  std::vector<Vec> force;         //!< internal + external [N]
  std::vector<Vec> velocity;      //!< at the start of the step [m/s]
  std::vector<Vec> velocity_new;  //!< after the update and the constraints [m/s]
  //! Damping force of the step (already in velocity_new) [N]: a constraint that fixes a
  //! component also takes its damping force, so reactions are the physical ones.
  std::vector<Vec> damping;

 private:
  Vec origin_;
  Vec size_;
  Vec cell_;
  std::array<int, D> cells_;
  std::array<bool, D> periodic_;
  std::array<long, D> stride_{};
};

}  // namespace mpm_lig::mpm
