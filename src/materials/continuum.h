#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "materials/elasticity.h"
#include "materials/material.h"
#include "materials/strain_increment.h"

namespace mpm_lig::materials {

//! What the continuum materials share: density, isotropic elasticity, one stress per point,
//! and the Hughes–Winget stress update (rotate, add the elastic trial increment, then let
//! the law correct the trial stress — the plastic return).
class ContinuumMaterial : public Material {
 public:
  ContinuumMaterial(double density, const Elasticity& elasticity)
      : density_(density), elasticity_(elasticity) {}

  double density() const override { return density_; }
  double wave_modulus() const override { return elasticity_.wave_modulus(); }
  std::size_t add_points(std::size_t count) override;
  void set_stress(std::size_t point, const Mat3& sigma) override;
  //! No symmetrisation: the rotation update leaves round-off asymmetry the run must keep.
  void restore_stress(std::size_t point, const Mat3& sigma) override { stress_.at(point) = sigma; }
  void update(const MaterialStep& step, std::vector<Mat3>& stress) override;

  const Elasticity& elasticity() const { return elasticity_; }
  //! Current stress of a point.
  const Mat3& stress(std::size_t point) const { return stress_.at(point); }
  std::size_t size() const { return stress_.size(); }

 protected:
  //! Bring `trial` (elastic predictor) back to the admissible set, updating the point's
  //! state. The default is elastic: nothing to correct.
  virtual Mat3 correct(std::size_t /*point*/, const Mat3& trial) { return trial; }
  //! Room for per-point state when points are added.
  virtual void resize_state(std::size_t /*count*/) {}

 private:
  double density_;
  Elasticity elasticity_;
  std::vector<Mat3> stress_;
};

}  // namespace mpm_lig::materials
