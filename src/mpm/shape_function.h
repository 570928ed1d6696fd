#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/registry.h"

namespace mpm_lig::mpm {

//! Most grid nodes a point touches along one axis (GIMP and quadratic kinds: 3).
inline constexpr int kMaxSupport1d = 3;

//! Weights of one point along one axis: nodes first .. first + count - 1.
struct Weights1d {
  int first = 0;
  int count = 0;
  std::array<double, kMaxSupport1d> value{};
  std::array<double, kMaxSupport1d> gradient{};  //!< d value / dx  [1/m]
};

//! A one-dimensional shape-function kind; the D-dimensional functions are tensor products.
//!
//! `xi` is the point coordinate in cell units from the grid origin, `half_length` the
//! point's half size in cell units (used by GIMP), `cell` the cell size [m].
class ShapeFunction1d {
 public:
  virtual ~ShapeFunction1d() = default;
  //! Name in the case file ("linear", "gimp").
  virtual std::string name() const = 0;
  //! Nodes per axis a point can touch.
  virtual int support() const = 0;
  virtual Weights1d weights(double xi, double half_length, double cell) const = 0;
};

//! Linear hat functions: 2 nodes per axis; the gradient jumps when a point crosses a cell face.
class LinearShape final : public ShapeFunction1d {
 public:
  std::string name() const override { return "linear"; }
  int support() const override { return 2; }
  Weights1d weights(double xi, double half_length, double cell) const override;
};

//! Uniform GIMP (generalised interpolation material point): the hat function convolved
//! with the point's characteristic function of half length lp (fixed at its initial size).
//! Continuous gradient, so no cell-crossing noise; needs lp < cell / 2.
class GimpShape final : public ShapeFunction1d {
 public:
  std::string name() const override { return "gimp"; }
  int support() const override { return 3; }
  Weights1d weights(double xi, double half_length, double cell) const override;
};

//! Shape-function kinds by case-file name.
using ShapeRegistry = Registry<ShapeFunction1d>;

//! The registry with every kind mpm_lig ships ("linear", "gimp").
const ShapeRegistry& shape_registry();

//! Shape functions of one point in D dimensions: node indices, values, gradients.
template <int D>
struct PointWeights {
  static constexpr int kMaxNodes = D == 2 ? 9 : 27;
  int count = 0;
  std::array<long, kMaxNodes> node{};
  std::array<double, kMaxNodes> value{};
  std::array<Eigen::Matrix<double, D, 1>, kMaxNodes> gradient{};
};

}  // namespace mpm_lig::mpm
