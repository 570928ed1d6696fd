#pragma once

#include <array>
#include <vector>

#include <Eigen/Dense>

#include "mpm/grid.h"
#include "mpm/particles.h"

namespace mpm_lig::mpm {

//! A second-gradient energy on the deformation field, the regularisation of
//! `analysis.internal_length` (docs/methods.md §7): E = ½ D Σ_p V⁰_p |∇₀F_p|², with ∇₀F_p the
//! weighted least-squares gradient of the points' deformation gradients over the points
//! within 1.5 cells of p in the reference configuration (positions at the start of the main
//! stage, initial volumes V⁰): E is a function of the points' F alone, so the forces, its
//! derivative in F, conserve energy (with volumetric smoothing after the solver passes them
//! through the smoothing's work-conjugate, KinematicsOperator::pull_back).
//! (A gradient through the nodes, F projected to the nodes and
//! differentiated with the shape functions, cannot see a strain alternating cell by cell: the
//! projection averages it away, and a softening layer fills with that pattern.)
//! The materials are not touched: a DEM point's RVE sees the same F as without it; the energy
//! adds to each point's internal-force tensor V σ a tensor S with the same form,
//! f_i = −Σ_p (V_p σ_p + S_p) ∇N_i(x_p), where S_p : L_p is the point's share of dE/dt
//! (Ḟ_p = L_p F_p).
//!
//! In a band where the material softens with tangent shear modulus −G_s, equilibrium
//! σ − D γ'' = const makes the band's strain increment a cosine of full width at half height
//! ℓ = π √(D / G_s): the case gives ℓ and G_s, D = G_s (ℓ/π)².
//!
//! With a yield gradient κ_y (`internal_length.yield_strain` ε_y over ℓ; 2D) the energy is
//! E = ½ D Σ_p V⁰_p |R_pᵀ∇₀F_p − K_p|², R_p the polar rotation of F_p: K_p, the gradient's
//! relaxed part, follows R_pᵀ∇₀F_p wherever the difference exceeds κ_y (relax(), a return to
//! the limit after each step), so the stored energy stays below ½ D κ_y² Σ V⁰ and the work a
//! band's slip puts into its gradient beyond the limit is dissipated (dissipated()). Without it
//! the energy of the total gradient grows with the slip squared. K is held in the point's
//! rotated frame, so a rigid rotation changes nothing (a K in the fixed frame would see a
//! rotated band's whole gradient as new). K is state: checkpointed, the same on every rank.
//!
//! What it keeps: the forces sum to zero (Σ_i ∇N_i = 0: momentum); E depends on F only
//! through |∇₀F|, unchanged by a rigid rotation F → Q F, so a rotation adds no force and the
//! torque of the forces vanishes; no state of its own (F and the reference positions are the
//! points' state, checkpointed), so a resume and any rank count give the same forces. A uniform F
//! has ∇F = 0 exactly (differences).
//!
//! The fitted gradient cannot see the shortest wave: with weights odd in the offset, a strain
//! alternating from one point column to the next has ∇₀F = 0 (a wave of number k is seen as
//! sin(kh)/h of its gradient), so a softening material may fill with that pattern at no cost
//! (docs/methods.md §7, the odd-even mode). With a residual weight β > 0 the energy adds what
//! the fit leaves out, E_r = ½ D β Σ_p V⁰_p Σ_q ŵ_pq |F_q − F_p − ∇₀F_p dX_pq|² / |dX_pq|²
//! (ŵ the fit's weights normalised to sum 1 over p's neighbours): zero for a linear F, so
//! smooth fields keep the gradient's energy, and largest for the alternation (on a lattice of
//! one point a cell, 2 β D / h² times its strain amplitude squared per unit volume for
//! alternate columns). β = 0 leaves the arithmetic as it was.
template <int D>
class SecondGradient {
 public:
  using Matrix = Eigen::Matrix<double, D, D>;

  //! D [Pa m²] from the length ℓ [m] and the softening modulus G_s [Pa]; a yield gradient
  //! κ_y [1/m] > 0 bounds the stored gradient (0: unbounded).
  //! β ≥ 0 weighs the fit's residual energy (0: none).
  SecondGradient(double length, double softening_modulus, double yield_gradient = 0.0,
                 double residual_weight = 0.0);
  static double modulus(double length, double softening_modulus);
  double modulus() const { return modulus_; }

  //! One neighbour q of a point p and its least-squares weight vector b: ∇₀f_p = Σ_q (f_q − f_p)
  //! bᵀ; its reference offset dX = X_q − X_p and its share ŵ / |dX|² of the residual energy.
  struct Neighbour {
    std::size_t point;
    Eigen::Matrix<double, D, 1> weight;
    Eigen::Matrix<double, D, 1> offset;
    double residual_share;
  };
  using NeighbourLists = std::vector<std::vector<Neighbour>>;

  //! S_p for every point from the points' reference positions, initial volumes and F.
  void force_tensors(const Particles<D>& particles, const Grid<D>& grid,
                     std::vector<Matrix>& out) const;
  //! E = ½ D Σ_p V⁰_p |R_pᵀ∇₀F_p − K_p|² (K = 0 unbounded: |∇₀F_p|²), plus the residual
  //! energy E_r with β > 0 [J per unit thickness in 2D]: what force_tensors differentiates.
  double energy(const Particles<D>& particles, const Grid<D>& grid) const;

  //! With a yield gradient: K_p ← K_p + (1 − κ_y/|r|) r where r = R_pᵀ∇₀F_p − K_p exceeds it (after
  //! the step's deformation), the energy given up booked as dissipated. Nothing without one.
  void relax(const Particles<D>& particles, const Grid<D>& grid);
  //! Zero every K_p and the dissipation booked: a new reference configuration (the main
  //! stage's start).
  void forget_relaxation() {
    relaxed_.clear();
    dissipated_ = 0.0;
  }
  bool bounded() const { return yield_gradient_ > 0.0; }
  double residual_weight() const { return residual_weight_; }
  //! The energy the relaxations gave up so far [J per unit thickness in 2D].
  double dissipated() const { return dissipated_; }
  //! K as D·D·D doubles a point and the dissipated energy last (a checkpoint's record), and
  //! back; `points` points.
  std::vector<double> relaxation_state(std::size_t points) const;
  void restore_relaxation(const std::vector<double>& state, std::size_t points);

 private:
  //! The neighbour lists of the points' reference configuration, built again only when it is
  //! not the one they were built for (the main stage's start, a resume, another body): the
  //! reference does not move within a stage, so the lists are built once, not every step.
  const NeighbourLists& neighbours(const Particles<D>& particles, const Grid<D>& grid) const;

  //! ∇₀F_p ([c] = ∂F/∂X_c), or with a relaxed part R_pᵀ∇₀F_p − K_p.
  std::array<Matrix, D> elastic_gradient(const Particles<D>& particles, std::size_t p,
                                         const std::vector<Neighbour>& list) const;

  //! Σ_q ŵ_q |r_q|² / |dX_q|² at p, r_q = F_q − F_p − ∇₀F_p dX_q (∇₀F_p the total gradient,
  //! not its relaxed part's: the residual is not bounded); with `share_out` also the residuals
  //! times their shares, ŵ_q r_q / |dX_q|², in the list's order.
  double residual_sum(const Particles<D>& particles, std::size_t p,
                      const std::vector<Neighbour>& list, const std::array<Matrix, D>& gradient,
                      std::vector<Matrix>* share_out) const;
  //! Adds ∂E_r,p/∂F to every Π (`scale` = D β V⁰_p, `gradient` the total ∇₀F_p).
  void add_residual_derivative(const Particles<D>& particles, std::size_t p,
                               const std::vector<Neighbour>& list, double scale,
                               const std::array<Matrix, D>& gradient,
                               std::vector<Matrix>& pi) const;

  double modulus_;
  double yield_gradient_;
  double residual_weight_;
  std::vector<std::array<Matrix, D>> relaxed_;  // K_p; empty: all zero
  double dissipated_ = 0.0;
  mutable std::vector<Eigen::Matrix<double, D, 1>> built_for_;  // reference positions
  mutable double built_reach_ = 0.0;
  mutable NeighbourLists neighbours_;
};

}  // namespace mpm_lig::mpm
