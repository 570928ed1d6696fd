#include "element/strain_path.h"

#include <algorithm>
#include <cmath>

#include "element/recorded_path.h"

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

//! Axial compression (y in 2D, z in 3D) at constant lateral stress. Each increment applies the
//! axial step with a predicted lateral strain; corrections within the increment then change
//! only the lateral lengths until every lateral stress is within the tolerance. The prediction
//! learns from the error each increment's own step left before its corrections (integral
//! action: the steady dilatancy, and the lower stress read while the packing is being sheared
//! than after it rested in a correction). The lateral stiffness is re-estimated from the
//! response to each correction (axial length fixed: the change of lateral stress is the lateral
//! response alone), separately for widening (unloading towards failure: soft) and narrowing
//! (reloading: stiff, measured up to 4 times the widening stiffness near the peak).
class DrainedPath : public StrainPath {
 public:
  DrainedPath(const ElementTestSpec& t, int dimension, double confining, double stiffness)
      : n_(count(t.strain, t.strain_increment)),
        step_(t.strain / n_),
        lateral_axes_(dimension - 1),
        confining_(confining),
        tolerance_(t.confining_tolerance * confining),
        stiffness_(stiffness) {}
  int increments() const override { return n_; }

  Mat3 increment(int k, const Mat3& stress) override {
    Mat3 dF = Mat3::Identity();
    dF(lateral_axes_, lateral_axes_) = std::exp(-step_);
    for (int i = 0; i < lateral_axes_; ++i) {
      if (k > 0)
        trend_[i] += kTrendGain * after_step_[i] / stiffness(after_step_[i]);
      dF(i, i) = std::exp(trend_[i] + excess(stress, i) / stiffness(excess(stress, i)));
    }
    last_correction_ = false;
    return dF;
  }

  std::optional<Mat3> correction(const Mat3& stress) override {
    if (last_correction_)
      update_stiffness(stress);
    else
      for (int i = 0; i < lateral_axes_; ++i)
        after_step_[i] = excess(stress, i);
    double worst = 0.0;
    for (int i = 0; i < lateral_axes_; ++i)
      worst = std::max(worst, std::abs(excess(stress, i)));
    if (worst <= tolerance_)
      return std::nullopt;
    Mat3 dF = Mat3::Identity();
    for (int i = 0; i < lateral_axes_; ++i) {
      applied_[i] = excess(stress, i) / stiffness(excess(stress, i));
      before_[i] = -stress(i, i);
      dF(i, i) = std::exp(applied_[i]);
    }
    last_correction_ = true;
    return dF;
  }

 private:
  //! Compression-positive lateral stress above the target (> 0: the cell must widen).
  double excess(const Mat3& stress, int i) const { return -stress(i, i) - confining_; }

  //! The stiffness estimate for a lateral strain of the sign of `widen` (> 0: widening).
  double& stiffness(double widen) { return stiffness_(widen); }

  //! Secant stiffness of the last correction (-Δσ'/Δε, least squares over the lateral axes).
  void update_stiffness(const Mat3& stress) {
    double num = 0.0, den = 0.0, sum = 0.0;
    for (int i = 0; i < lateral_axes_; ++i) {
      num += (before_[i] + stress(i, i)) * applied_[i];  // -(Δσ'_i) Δε_i with σ' = -σ
      den += applied_[i] * applied_[i];
      sum += applied_[i];
    }
    stiffness_.update(num, den, sum);
  }

  int n_;
  double step_;
  int lateral_axes_;
  double confining_;
  double tolerance_;
  ServoStiffness stiffness_;           //!< lateral stiffness estimates per direction
  double trend_[2] = {0.0, 0.0};       //!< predicted lateral log strain per increment step
  double after_step_[2] = {0.0, 0.0};  //!< lateral stress error the last step left [Pa]
  static constexpr double kTrendGain = 0.5;
  double applied_[2] = {0.0, 0.0};  //!< lateral log strain of the last correction
  double before_[2] = {0.0, 0.0};   //!< lateral stress (compression positive) before it
  bool last_correction_ = false;
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

void ServoStiffness::update(double num, double den, double direction) {
  if (!(den > 0.0) || !(num > 0.0))
    return;
  double& k = (*this)(direction);
  k = std::clamp(std::sqrt(k * num / den), first_ / 50.0, 4.0 * first_);
}

std::unique_ptr<StrainPath> make_strain_path(const ElementTestSpec& test, int dimension,
                                             double confining_pressure, double lateral_stiffness) {
  switch (test.kind) {
    case TestKind::kIsotropicCompression:
      return std::make_unique<IsotropicPath>(test, dimension);
    case TestKind::kDrainedCompression:
      return std::make_unique<DrainedPath>(test, dimension, confining_pressure, lateral_stiffness);
    case TestKind::kUndrainedCyclicSimpleShear:
      return std::make_unique<CyclicSimpleShearPath>(test);
    case TestKind::kRecordedPath:
      return make_recorded_strain_path(test.recorded, dimension, lateral_stiffness);
  }
  return nullptr;
}

}  // namespace mpm_lig::element
