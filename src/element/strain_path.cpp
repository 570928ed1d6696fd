#include "element/strain_path.h"

#include <cmath>

namespace mpm_lig::element {
namespace {

int count(double total, double step) {
  return std::max(1, static_cast<int>(std::ceil(total / step - 1e-9)));
}

//! Equal per-axis compression (in-plane in 2D) by log strain `strain` in total.
class IsotropicPath : public StrainPath {
 public:
  IsotropicPath(const ElementTestSpec& t, int dimension)
      : n_(count(t.strain, t.strain_increment)), step_(t.strain / n_), dimension_(dimension) {}
  int increments() const override { return n_; }
  Mat3 increment(int, const Mat3&) override {
    Mat3 dF = Mat3::Identity() * std::exp(-step_);
    if (dimension_ == 2)
      dF(2, 2) = 1.0;
    return dF;
  }

 private:
  int n_;
  double step_;
  int dimension_;
};

//! Axial compression (y in 2D, z in 3D) at constant lateral stress: each lateral direction
//! gets the strain that cancels its stress error, with a gain below the lateral stiffness.
class DrainedPath : public StrainPath {
 public:
  DrainedPath(const ElementTestSpec& t, int dimension, double confining, double stiffness)
      : n_(count(t.strain, t.strain_increment)),
        step_(t.strain / n_),
        dimension_(dimension),
        confining_(confining),
        stiffness_(stiffness) {}
  int increments() const override { return n_; }
  Mat3 increment(int, const Mat3& stress) override {
    Mat3 dF = Mat3::Identity();
    const int axial = dimension_ - 1;
    dF(axial, axial) = std::exp(-step_);
    for (int i = 0; i < axial; ++i) {
      // Compression positive lateral stress above the target: let the cell expand.
      const double excess = -stress(i, i) - confining_;
      // Proportional-integral: the integral removes the lag behind the steady dilatancy.
      integral_[i] += excess;
      dF(i, i) = std::exp((excess + kIntegralGain * integral_[i]) / stiffness_);
    }
    return dF;
  }

 private:
  int n_;
  double step_;
  int dimension_;
  double confining_;
  double stiffness_;
  static constexpr double kIntegralGain = 0.3;
  double integral_[2] = {0.0, 0.0};
};

//! Constant-volume simple shear γ_xy (x moves with y), triangular cycles 0 → γa → −γa → 0.
class CyclicSimpleShearPath : public StrainPath {
 public:
  explicit CyclicSimpleShearPath(const ElementTestSpec& t)
      : quarter_(count(t.shear_amplitude, t.strain_increment)),
        step_(t.shear_amplitude / quarter_),
        cycles_(t.cycles) {}
  int increments() const override { return 4 * quarter_ * cycles_; }
  Mat3 increment(int k, const Mat3&) override {
    const int phase = k % (4 * quarter_);
    const double sign = phase < quarter_ || phase >= 3 * quarter_ ? 1.0 : -1.0;
    Mat3 dF = Mat3::Identity();
    dF(0, 1) = sign * step_;
    return dF;
  }

 private:
  int quarter_;
  double step_;
  int cycles_;
};

}  // namespace

std::unique_ptr<StrainPath> make_strain_path(const ElementTestSpec& test, int dimension,
                                             double confining_pressure, double lateral_stiffness) {
  switch (test.kind) {
    case TestKind::kIsotropicCompression:
      return std::make_unique<IsotropicPath>(test, dimension);
    case TestKind::kDrainedCompression:
      return std::make_unique<DrainedPath>(test, dimension, confining_pressure, lateral_stiffness);
    case TestKind::kUndrainedCyclicSimpleShear:
      return std::make_unique<CyclicSimpleShearPath>(test);
  }
  return nullptr;
}

}  // namespace mpm_lig::element
