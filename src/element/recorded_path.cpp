#include "element/recorded_path.h"

#include <cmath>
#include <cstdio>

#include <Eigen/LU>

#include "element/path_csv.h"
#include "element/strain_path.h"
#include "io/point_history.h"

namespace mpm_lig::element {
namespace {

//! The datasets of results.h5 a replay reads (output.deformation_gradient of the MPM run).
constexpr const char* kDeformation = "deformation_gradient";
constexpr const char* kIncrement = "deformation_increment";

bool is_plane(const Mat3& F) {
  return F(0, 2) == 0.0 && F(1, 2) == 0.0 && F(2, 0) == 0.0 && F(2, 1) == 0.0 && F(2, 2) == 1.0;
}

Mat3 row_major(const std::vector<double>& row) {
  Mat3 F;
  for (int c = 0; c < 9; ++c)
    F(c / 3, c % 3) = row[c];
  return F;
}

std::string shown(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

//! Why `F` cannot be a state (or increment) of a path for an RVE of `dimension`, or "".
std::string problem_of(const Mat3& F, int dimension, const char* name) {
  for (int c = 0; c < 9; ++c) {
    if (!std::isfinite(F(c / 3, c % 3)))
      return std::string(name) + std::to_string(c / 3 + 1) + std::to_string(c % 3 + 1) + " is " +
             shown(F(c / 3, c % 3));
  }
  if (!(F.determinant() > 0.0))
    return std::string("det ") + name + " = " + shown(F.determinant()) + ", must be > 0";
  if (dimension == 2 && !is_plane(F))
    return std::string("a 2D RVE takes plane deformation only: ") + name + "13, " + name + "23, " +
           name + "31, " + name + "32 must be 0 and " + name + "33 1 (a 3D path)";
  return "";
}

//! Every row's F and time, and every recorded increment, checked; the first problem fails `key`.
void check_rows(const RecordedPath& path, int dimension, const CaseNode& node,
                const std::string& key) {
  const std::string file = "'" + path.source + "' ";
  if (path.F.size() < 2)
    node.fail(key, file + "holds " + std::to_string(path.F.size()) +
                       " recorded state(s): a path needs at least two");
  for (std::size_t k = 0; k < path.F.size(); ++k) {
    const std::string where = file + path.label[k] + ": ";
    if (!std::isfinite(path.time[k]))
      node.fail(key, where + "time is " + shown(path.time[k]));
    if (k > 0 && !(path.time[k] > path.time[k - 1]))
      node.fail(key, where + "time " + shown(path.time[k]) + " is not after the previous row's " +
                         shown(path.time[k - 1]) + " (times must increase)");
    const std::string problem = problem_of(path.F[k], dimension, "F");
    if (!problem.empty())
      node.fail(key, where + problem);
    if (k > 0 && path.recorded_increment[k - 1]) {
      const std::string p = problem_of(*path.recorded_increment[k - 1], dimension, "dF");
      if (!p.empty())
        node.fail(key, where + kIncrement + ": " + p);
    }
  }
}

//! The DEM steps of every interval of `path` as the recording run ran them (`substeps`:
//! "recorded"): its field dem_substeps_m<id> for the point's material, each interval one MPM
//! step. What makes the first update bit for bit: a clone in the coupling has not read its
//! stress before it, so the rule counts it at substeps.pressure_floor, while an element test
//! has read the prepared packing's (docs/methods.md §6).
void take_recorded_substeps(const CaseNode& node, const io::PointHistory& h, RecordedPath& path) {
  const std::vector<double>& material = h.rows.at("material").front();
  if (material.size() != 1)
    node.fail("substeps", "'" + path.source + "' " + h.group.front() +
                              " has no dataset 'material': its point's sub-steps are unknown");
  const std::string field = "dem_substeps_m" + std::to_string(std::lround(material[0]));
  io::PointHistory counts;
  try {
    counts = io::read_point_history(path.source, static_cast<std::size_t>(path.point), {field});
  } catch (const io::PointHistoryError& e) {
    node.fail("substeps", std::string(e.what()) + " (is point " + std::to_string(path.point) +
                              " a dem_rve point?)");
  }
  for (std::size_t k = 1; k < h.step.size(); ++k) {
    const std::string where = "'" + path.source + "' " + h.group[k] + ": ";
    if (h.step[k] != h.step[k - 1] + 1)
      node.fail("substeps",
                where + "follows " + h.group[k - 1] +
                    ": recorded sub-steps need every MPM step written (output.every 1)");
    const double n = counts.rows.at(field)[k].front();
    if (!(n >= 1.0 && n <= 1e9 && n == std::floor(n)))
      node.fail("substeps", where + field + " is " + shown(n) +
                                ": the point ran no DEM update there (a quiet point or a "
                                "continuum start), so its path cannot be replayed step by step");
    path.substeps[k - 1] = static_cast<int>(n);
  }
}

//! Point `point` of an mpm_lig run's results.h5: its F at every output step, and the step's own
//! increment where consecutive output steps are one MPM step apart.
RecordedPath read_results_path(const CaseNode& node) {
  const std::string file = node.file_path("results");
  const long point = node.get<long>("point");
  if (point < 0)
    node.fail("point", "must be >= 0, got " + std::to_string(point));
  const bool recorded_substeps =
      node.choice_or("substeps", {"rule", "recorded"}, "rule") == "recorded";
  io::PointHistory h;
  try {
    h = io::read_point_history(file, static_cast<std::size_t>(point), {},
                               {kDeformation, kIncrement, "material"});
  } catch (const io::UnknownPointError& e) {
    node.fail("point", "no point " + std::to_string(point) + ": " + e.what());
  } catch (const io::PointHistoryError& e) {
    node.fail("results", e.what());
  }
  RecordedPath path;
  path.source = file;
  path.point = point;
  for (std::size_t k = 0; k < h.step.size(); ++k) {
    const std::vector<double>& F = h.rows[kDeformation][k];
    const std::vector<double>& dF = h.rows[kIncrement][k];
    if (F.size() != 9)
      node.fail("results", "'" + file + "' " + h.group[k] + " has no dataset " + kDeformation +
                               " (n x 9): run the case with output.deformation_gradient true "
                               "(the strain field alone has lost the rotation)");
    path.label.push_back(h.group[k]);
    path.time.push_back(h.time[k]);
    path.F.push_back(row_major(F));
    if (k > 0) {
      const bool one_step = h.step[k] == h.step[k - 1] + 1 && dF.size() == 9;
      path.recorded_increment.push_back(one_step ? std::optional<Mat3>(row_major(dF))
                                                 : std::nullopt);
      path.substeps.push_back(0);
    }
  }
  if (recorded_substeps)
    take_recorded_substeps(node, h, path);
  return path;
}

//! "volume": "free" (the mean stress of column p held, the isochoric part of F imposed) or
//! "recorded" (the default: F as recorded, p ignored).
void read_volume_control(const CaseNode& node, RecordedPath& path) {
  path.free_volume = node.choice_or("volume", {"recorded", "free"}, "recorded") == "free";
  if (!path.free_volume)
    return;
  path.pressure_tolerance = node.in_range_or("pressure_tolerance", 1e-4, 0.1, 0.005);
  if (path.mean_stress.size() != path.F.size())
    node.fail("volume",
              "free needs a CSV path (csv) with a column p: the mean stress [Pa] "
              "to hold the RVE at");
  for (std::size_t k = 0; k < path.F.size(); ++k)
    if (!(std::isfinite(path.mean_stress[k]) && path.mean_stress[k] > 0.0))
      node.fail("volume", "'" + path.source + "' " + path.label[k] + ": p is " +
                              shown(path.mean_stress[k]) + ", must be finite and > 0");
}

class RecordedStrainPath : public StrainPath {
 public:
  explicit RecordedStrainPath(std::shared_ptr<const RecordedPath> path) : path_(std::move(path)) {}
  int increments() const override { return static_cast<int>(path_->intervals()); }
  Mat3 increment(int k, const Mat3&) override { return path_->increment(k); }
  int substeps(int k) const override { return path_->substeps[k]; }
  Mat3 start() const override { return path_->F.front(); }

 private:
  std::shared_ptr<const RecordedPath> path_;
};

//! A recorded path with a free volume: each increment imposes the isochoric part of the
//! recorded one (its volume scaled out, in the plane for a 2D RVE) times a predicted isotropic
//! stretch; corrections within the increment then stretch the cell isotropically until its mean
//! stress is the recorded row's. As the drained test's servo (strain_path.cpp): the prediction
//! learns the steady dilatancy from the error each increment's own step left, and the
//! stiffness is re-estimated from each correction's response (ServoStiffness).
class FreeVolumePath : public StrainPath {
 public:
  FreeVolumePath(std::shared_ptr<const RecordedPath> path, int dimension, double stiffness)
      : path_(std::move(path)), axes_(dimension), stiffness_(stiffness) {}
  int increments() const override { return static_cast<int>(path_->intervals()); }
  int substeps(int k) const override { return path_->substeps[k]; }
  Mat3 start() const override { return path_->F.front(); }

  Mat3 increment(int k, const Mat3& stress) override {
    target_ = path_->mean_stress[k + 1];
    if (k > 0)
      trend_ += kTrendGain * after_step_ / stiffness(after_step_);
    const Mat3 dF = path_->increment(k);
    const double volume = axes_ == 2 ? dF.topLeftCorner<2, 2>().determinant() : dF.determinant();
    last_correction_ = false;
    return isotropic(trend_ + excess(stress) / stiffness(excess(stress)) -
                     std::log(volume) / axes_) *
           dF;
  }

  std::optional<Mat3> correction(const Mat3& stress) override {
    if (last_correction_)
      update_stiffness(stress);
    else
      after_step_ = excess(stress);
    if (std::abs(excess(stress)) <= path_->pressure_tolerance * target_)
      return std::nullopt;
    applied_ = excess(stress) / stiffness(excess(stress));
    before_ = mean(stress);
    last_correction_ = true;
    return isotropic(applied_);
  }

 private:
  //! Compression-positive mean stress over the axes (in-plane in 2D).
  double mean(const Mat3& stress) const {
    return axes_ == 2 ? -0.5 * (stress(0, 0) + stress(1, 1)) : -stress.trace() / 3.0;
  }
  //! Mean stress above the target (> 0: the cell must expand).
  double excess(const Mat3& stress) const { return mean(stress) - target_; }
  double& stiffness(double expand) { return stiffness_(expand); }
  //! Equal log stretch `e` of every axis (in the plane for a 2D RVE).
  Mat3 isotropic(double e) const {
    Mat3 dF = Mat3::Identity();
    for (int i = 0; i < axes_; ++i)
      dF(i, i) = std::exp(e);
    return dF;
  }
  void update_stiffness(const Mat3& stress) {
    const double response = before_ - mean(stress);  // the fall of the mean stress
    stiffness_.update(response * applied_, applied_ * applied_, applied_);
  }

  std::shared_ptr<const RecordedPath> path_;
  int axes_;
  ServoStiffness stiffness_;  //!< per unit per-axis log strain
  double target_ = 0.0;       //!< the mean stress of the increment's end row
  double trend_ = 0.0;        //!< predicted per-axis log strain per increment
  double after_step_ = 0.0;   //!< mean-stress error the last step left [Pa]
  static constexpr double kTrendGain = 0.5;
  double applied_ = 0.0;  //!< per-axis log strain of the last correction
  double before_ = 0.0;   //!< mean stress before it
  bool last_correction_ = false;
};

//! ΔF·M = T for square M, T of size N: ΔF's rows solve Mᵀ xᵢ = tᵢ one by one. Eigen divides by
//! the pivots for a vector right-hand side but multiplies by their reciprocals for a matrix one,
//! and only the division gives a diagonal path's quotients exactly (one rounding).
template <int N>
Eigen::Matrix<double, N, N> right_solve(const Eigen::Matrix<double, N, N>& M,
                                        const Eigen::Matrix<double, N, N>& T) {
  const Eigen::PartialPivLU<Eigen::Matrix<double, N, N>> lu(M.transpose());
  Eigen::Matrix<double, N, N> X;
  for (int i = 0; i < N; ++i)
    X.row(i) = lu.solve(Eigen::Matrix<double, N, 1>(T.row(i).transpose())).transpose();
  return X;
}

}  // namespace

Mat3 increment_between(const Mat3& from, const Mat3& to) {
  // No explicit inverse (its cofactors would round even a diagonal F), and a plane pair solved
  // in the plane so that the out-of-plane part is exactly the identity.
  if (is_plane(from) && is_plane(to)) {
    Mat3 dF = Mat3::Identity();
    dF.topLeftCorner<2, 2>() = right_solve<2>(from.topLeftCorner<2, 2>(), to.topLeftCorner<2, 2>());
    return dF;
  }
  return right_solve<3>(from, to);
}

Mat3 RecordedPath::increment(std::size_t k) const {
  return recorded_increment[k] ? *recorded_increment[k] : increment_between(F[k], F[k + 1]);
}

std::shared_ptr<const RecordedPath> read_recorded_path(const CaseNode& node, int dimension) {
  if (node.has("csv") == node.has("results"))
    node.fail(
        "give exactly one of csv (a CSV file of F(t)) and results (an mpm_lig run's "
        "results.h5, with point)");
  RecordedPath path;
  std::string key = "results";
  if (node.has("csv")) {
    key = "csv";
    if (node.has("point"))
      node.fail("point", "belongs to a results.h5 path (results), not to a CSV file");
    try {
      path = read_path_csv(node.file_path("csv"));
    } catch (const PathFileError& e) {
      node.fail("csv", e.what());
    }
  } else {
    path = read_results_path(node);
  }
  check_rows(path, dimension, node, key);
  read_volume_control(node, path);
  return std::make_shared<const RecordedPath>(std::move(path));
}

std::unique_ptr<StrainPath> make_recorded_strain_path(std::shared_ptr<const RecordedPath> path,
                                                      int dimension, double stiffness) {
  if (path->free_volume)
    return std::make_unique<FreeVolumePath>(std::move(path), dimension, stiffness);
  return std::make_unique<RecordedStrainPath>(std::move(path));
}

}  // namespace mpm_lig::element
