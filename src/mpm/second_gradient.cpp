#include "mpm/second_gradient.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "mpm/point_bins.h"

namespace mpm_lig::mpm {
namespace {

//! Neighbours within this many (largest) cells give a point's gradient.
constexpr double kReachInCells = 1.5;

}  // namespace

template <int D>
SecondGradient<D>::SecondGradient(double length, double softening_modulus, double yield_gradient,
                                  double residual_weight)
    : modulus_(modulus(length, softening_modulus)),
      yield_gradient_(yield_gradient),
      residual_weight_(residual_weight) {
  if (!(modulus_ > 0.0) || !std::isfinite(modulus_))
    throw std::invalid_argument("SecondGradient: length and softening modulus must be > 0");
  if (!(yield_gradient_ >= 0.0) || !std::isfinite(yield_gradient_))
    throw std::invalid_argument("SecondGradient: the yield gradient must be >= 0");
  if (D != 2 && yield_gradient_ > 0.0)
    throw std::invalid_argument("SecondGradient: a yield gradient is 2D only");
  if (!(residual_weight_ >= 0.0) || !std::isfinite(residual_weight_))
    throw std::invalid_argument("SecondGradient: the residual weight must be >= 0");
}

template <int D>
double SecondGradient<D>::modulus(double length, double softening_modulus) {
  const double pi = std::acos(-1.0);
  return softening_modulus * (length / pi) * (length / pi);
}

namespace {

//! Each point's neighbours and least-squares weights in the reference configuration (the
//! points' positions at the start of the main stage): with w_q = 1 − (r/R)², M = Σ w dX dXᵀ,
//! b_q = w_q M⁻¹ dX_q, the fit's gradient is Σ_q (f_q − f_p) b_qᵀ (exact for a linear f). A
//! point whose neighbours do not span the plane (M singular) gets none: no gradient. The
//! residual's shares are w_q / (Σ w |dX_q|²).
//! Why the reference and not the current positions: the forces are ∂E/∂F only, so E must
//! depend on nothing else that moves. Weights from the current positions made E change as
//! neighbours closed in or drew apart, work that no force did, and on the footing that
//! unaccounted energy fed an oscillation of neighbouring points which grew at a rate per unit
//! time that no shorter step removed (docs/methods.md §7).
template <int D>
std::vector<std::vector<typename SecondGradient<D>::Neighbour>> neighbours_of(
    const Particles<D>& particles, const Grid<D>& grid) {
  using Vec = Eigen::Matrix<double, D, 1>;
  const std::size_t n = particles.size();
  const double reach = kReachInCells * grid.cell().maxCoeff();
  PointBins<D> bins(grid, reach);
  for (std::size_t p = 0; p < n; ++p)
    bins.add(p, particles.reference[p]);
  std::vector<std::vector<typename SecondGradient<D>::Neighbour>> neighbours(n);
  std::vector<Vec> offsets;
  std::vector<double> weights;
  for (std::size_t p = 0; p < n; ++p) {
    std::vector<typename SecondGradient<D>::Neighbour>& list = neighbours[p];
    offsets.clear();
    weights.clear();
    Eigen::Matrix<double, D, D> moment = Eigen::Matrix<double, D, D>::Zero();
    for (const std::size_t box : bins.around(particles.reference[p])) {
      for (const std::size_t q : bins.members(box)) {
        if (q == p)
          continue;
        const Vec dx = separation(grid, particles.reference[p], particles.reference[q]);
        const double r2 = dx.squaredNorm() / (reach * reach);
        if (r2 >= 1.0)
          continue;
        list.push_back({q, Vec::Zero(), dx, 0.0});
        offsets.push_back(dx);
        weights.push_back(1.0 - r2);
        moment += (1.0 - r2) * dx * dx.transpose();
      }
    }
    const Eigen::FullPivLU<Eigen::Matrix<double, D, D>> lu(moment);
    if (list.size() < static_cast<std::size_t>(D) || !lu.isInvertible() || lu.rcond() < 1e-8) {
      list.clear();
      continue;
    }
    const Eigen::Matrix<double, D, D> inverse = lu.inverse();
    double weight_sum = 0.0;
    for (const double w : weights)
      weight_sum += w;
    for (std::size_t k = 0; k < list.size(); ++k) {
      list[k].weight = weights[k] * (inverse * offsets[k]);
      list[k].residual_share = weights[k] / (weight_sum * offsets[k].squaredNorm());
    }
  }
  return neighbours;
}

//! ∇₀F_p as D matrices, [c] = ∂F/∂X_c.
template <int D>
std::array<Eigen::Matrix<double, D, D>, D> gradient_at(
    const Particles<D>& particles, std::size_t p,
    const std::vector<typename SecondGradient<D>::Neighbour>& list) {
  using Matrix = Eigen::Matrix<double, D, D>;
  const Matrix fp = particles.deformation[p].template topLeftCorner<D, D>();
  std::array<Matrix, D> gradient;
  for (int c = 0; c < D; ++c)
    gradient[c].setZero();
  for (const typename SecondGradient<D>::Neighbour& nb : list) {
    const Matrix df = particles.deformation[nb.point].template topLeftCorner<D, D>() - fp;
    for (int c = 0; c < D; ++c)
      gradient[c] += df * nb.weight[c];
  }
  return gradient;
}

//! The rotation angle θ of a plane F (its polar rotation) and ∂θ/∂F.
struct PlaneRotation {
  Eigen::Matrix2d rotation;
  Eigen::Matrix2d angle_derivative;
};
PlaneRotation plane_rotation_of(const Mat3& f) {
  const double a = f(0, 0) + f(1, 1), b = f(1, 0) - f(0, 1);
  const double m = a * a + b * b;
  const double theta = std::atan2(b, a);
  PlaneRotation r;
  r.rotation << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  r.angle_derivative << -b / m, -a / m, a / m, -b / m;
  return r;
}

}  // namespace

template <int D>
const typename SecondGradient<D>::NeighbourLists& SecondGradient<D>::neighbours(
    const Particles<D>& particles, const Grid<D>& grid) const {
  const double reach = kReachInCells * grid.cell().maxCoeff();
  if (reach != built_reach_ || particles.reference != built_for_) {
    neighbours_ = neighbours_of(particles, grid);
    built_for_ = particles.reference;
    built_reach_ = reach;
  }
  return neighbours_;
}

template <int D>
std::array<typename SecondGradient<D>::Matrix, D> SecondGradient<D>::elastic_gradient(
    const Particles<D>& particles, std::size_t p, const std::vector<Neighbour>& list) const {
  std::array<Matrix, D> gradient = gradient_at(particles, p, list);
  if constexpr (D == 2) {
    if (!relaxed_.empty()) {
      const Matrix rotation = plane_rotation_of(particles.deformation[p]).rotation;
      for (int c = 0; c < D; ++c)
        gradient[c] = rotation.transpose() * gradient[c] - relaxed_[p][c];
    }
  }
  return gradient;
}

template <int D>
double SecondGradient<D>::residual_sum(const Particles<D>& particles, std::size_t p,
                                       const std::vector<Neighbour>& list,
                                       const std::array<Matrix, D>& gradient,
                                       std::vector<Matrix>* share_out) const {
  const Matrix fp = particles.deformation[p].template topLeftCorner<D, D>();
  if (share_out)
    share_out->resize(list.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < list.size(); ++k) {
    Matrix r = particles.deformation[list[k].point].template topLeftCorner<D, D>() - fp;
    for (int c = 0; c < D; ++c)
      r -= gradient[c] * list[k].offset[c];
    sum += list[k].residual_share * r.squaredNorm();
    if (share_out)
      (*share_out)[k] = list[k].residual_share * r;
  }
  return sum;
}

template <int D>
void SecondGradient<D>::add_residual_derivative(const Particles<D>& particles, std::size_t p,
                                                const std::vector<Neighbour>& list, double scale,
                                                const std::array<Matrix, D>& gradient,
                                                std::vector<Matrix>& pi) const {
  // E_r,p = ½ scale Σ_q s_q |r_q|², r_q = F_q − F_p − Σ_c ∇₀F_p[c] dX_q[c]: directly through
  // F_q and F_p, and through the fit, ∂E_r,p/∂∇₀F_p[c] = −scale T[c], T[c] = Σ_q s_q r_q dX_q[c],
  // which reaches the F as the gradient's own term does (∂∇₀F_p[c]/∂F_k = b_k[c]).
  std::vector<Matrix> shares;
  residual_sum(particles, p, list, gradient, &shares);
  std::array<Matrix, D> through_fit;
  through_fit.fill(Matrix::Zero());
  for (std::size_t k = 0; k < list.size(); ++k) {
    pi[list[k].point] += scale * shares[k];
    pi[p] -= scale * shares[k];
    for (int c = 0; c < D; ++c)
      through_fit[c] += shares[k] * list[k].offset[c];
  }
  for (const Neighbour& nb : list) {
    Matrix share = Matrix::Zero();
    for (int c = 0; c < D; ++c)
      share += through_fit[c] * nb.weight[c];
    pi[nb.point] -= scale * share;
    pi[p] += scale * share;
  }
}

template <int D>
void SecondGradient<D>::relax(const Particles<D>& particles, const Grid<D>& grid) {
  if (!bounded())
    return;
  const NeighbourLists& lists = neighbours(particles, grid);
  const std::size_t n = particles.size();
  for (std::size_t p = 0; p < n; ++p) {
    if (lists[p].empty())
      continue;
    std::array<Matrix, D> r = elastic_gradient(particles, p, lists[p]);
    double squared = 0.0;
    for (int c = 0; c < D; ++c)
      squared += r[c].squaredNorm();
    const double size = std::sqrt(squared);
    if (size <= yield_gradient_)
      continue;
    if (relaxed_.empty()) {
      // Until the first point yields the energy is the unbounded one, bit for bit.
      std::array<Matrix, D> zero;
      zero.fill(Matrix::Zero());
      relaxed_.assign(n, zero);
      r = elastic_gradient(particles, p, lists[p]);  // now in the point's rotated frame
    }
    const double excess = 1.0 - yield_gradient_ / size;
    for (int c = 0; c < D; ++c)
      relaxed_[p][c] += excess * r[c];
    dissipated_ +=
        0.5 * modulus_ * particles.volume0[p] * (squared - yield_gradient_ * yield_gradient_);
  }
}

template <int D>
std::vector<double> SecondGradient<D>::relaxation_state(std::size_t points) const {
  constexpr std::size_t width = D * D * D;
  std::vector<double> state(points * width + 1, 0.0);
  for (std::size_t p = 0; p < relaxed_.size() && p < points; ++p)
    for (int c = 0; c < D; ++c)
      std::copy_n(relaxed_[p][c].data(), D * D, state.data() + p * width + c * D * D);
  state.back() = dissipated_;
  return state;
}

template <int D>
void SecondGradient<D>::restore_relaxation(const std::vector<double>& state, std::size_t points) {
  constexpr std::size_t width = D * D * D;
  if (state.size() != points * width + 1)
    throw std::runtime_error("the second gradient's relaxed part has " +
                             std::to_string(state.size()) + " values, " +
                             std::to_string(points * width + 1) + " expected");
  dissipated_ = state.back();
  relaxed_.clear();
  // All zero: no point had yielded, and the energy stays the unbounded one's arithmetic, as in
  // the run that wrote it (a point that yields gets a non-zero relaxed part).
  if (std::all_of(state.begin(), state.end() - 1, [](double v) { return v == 0.0; }))
    return;
  relaxed_.resize(points);
  for (std::size_t p = 0; p < points; ++p)
    for (int c = 0; c < D; ++c)
      relaxed_[p][c] = Eigen::Map<const Matrix>(state.data() + p * width + c * D * D);
}

template <int D>
void SecondGradient<D>::force_tensors(const Particles<D>& particles, const Grid<D>& grid,
                                      std::vector<Matrix>& out) const {
  const std::size_t n = particles.size();
  const NeighbourLists& lists = neighbours(particles, grid);
  // Π_q = ∂E/∂F_q: ∂(∇F_p[c])/∂F_q = b_pq[c] for q a neighbour, −Σ_q b_pq[c] for q = p.
  std::vector<Matrix> pi(n, Matrix::Zero());
  for (std::size_t p = 0; p < n; ++p) {
    if (lists[p].empty())
      continue;
    const std::array<Matrix, D> total = gradient_at(particles, p, lists[p]);
    std::array<Matrix, D> gradient = total;
    const double scale = modulus_ * particles.volume0[p];
    if constexpr (D == 2) {
      if (!relaxed_.empty()) {
        // E_p = ½ D V⁰ |r|², r = Rᵀ∇₀F − K: through ∇₀F as below with R r, and through the
        // rotation, ∂E_p/∂θ = −D V⁰ Σ_c r[c] : (J K[c]) (J the quarter turn; r : J r = 0).
        // The rotation once a point: r is elastic_gradient's, formed here from it.
        const PlaneRotation rotation = plane_rotation_of(particles.deformation[p]);
        Matrix quarter_turn;
        quarter_turn << 0.0, -1.0, 1.0, 0.0;
        double by_angle = 0.0;
        for (int c = 0; c < D; ++c) {
          const Matrix r = rotation.rotation.transpose() * gradient[c] - relaxed_[p][c];
          by_angle -= (r.array() * (quarter_turn * relaxed_[p][c]).array()).sum();
          gradient[c] = rotation.rotation * r;
        }
        pi[p] += scale * by_angle * rotation.angle_derivative;
      }
    }
    if (residual_weight_ > 0.0)
      add_residual_derivative(particles, p, lists[p], scale * residual_weight_, total, pi);
    for (const Neighbour& nb : lists[p]) {
      Matrix share = Matrix::Zero();
      for (int c = 0; c < D; ++c)
        share += gradient[c] * nb.weight[c];
      pi[nb.point] += scale * share;
      pi[p] -= scale * share;
    }
  }
  // S_p = Π_p F_pᵀ: Ḟ_p = L_p F_p, so Π_p : Ḟ_p = S_p : L_p.
  out.resize(n);
  for (std::size_t p = 0; p < n; ++p)
    out[p] = pi[p] * particles.deformation[p].template topLeftCorner<D, D>().transpose();
}

template <int D>
double SecondGradient<D>::energy(const Particles<D>& particles, const Grid<D>& grid) const {
  const NeighbourLists& lists = neighbours(particles, grid);
  double sum = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    if (lists[p].empty())
      continue;
    const std::array<Matrix, D> gradient = elastic_gradient(particles, p, lists[p]);
    double squared = 0.0;
    for (int c = 0; c < D; ++c)
      squared += gradient[c].squaredNorm();
    if (residual_weight_ > 0.0)
      squared += residual_weight_ *
                 residual_sum(particles, p, lists[p], gradient_at(particles, p, lists[p]), nullptr);
    sum += 0.5 * modulus_ * particles.volume0[p] * squared;
  }
  return sum;
}

template class SecondGradient<2>;
template class SecondGradient<3>;

}  // namespace mpm_lig::mpm
