// capacitance_solve.hpp — the reduced system S̃ y = b of a few held unknowns, solved with
// S's own Cholesky factor: the inverse of a principal submatrix from the inverse of the
// whole, through a small dense "capacitance" matrix (Proskurowski & Widlund, "On the
// numerical solution of Helmholtz's equation by the capacitance matrix method", Math.
// Comp. 30 (1976); Hager, "Updating the inverse of a matrix", SIAM Review 31 (1989)).
//
// S̃ y = b means y_A = b_A on the held unknowns A and S_II y_I = b_I on the free ones I.
// With P S Pᵀ = L Lᵀ, E_A the identity's columns of A and W = L⁻¹ P E_A, let
//     b̂ = b with b̂_A = 0,   v = L⁻¹ P b̂,   K μ = Wᵀ v   (K = Wᵀ W = E_Aᵀ S⁻¹ E_A),
//     ŷ = Pᵀ L⁻ᵀ (v − W μ) = S⁻¹ (b̂ − E_A μ).
// Then ŷ_A = E_Aᵀ S⁻¹ b̂ − K μ = 0 and (S ŷ)_I = b_I, so ŷ_I = y_I: one forward and one
// backward sweep — the cost of one solve with S's factor — plus |A| dot products, a
// dense |A| × |A| solve and a scatter, exact to round-off (K's condition is at most S's:
// its eigenvalues lie between those of S⁻¹).  An active-set method whose contact zone is
// a few unknowns (a membrane touching the obstacle here and there) thus pays the linear
// step's solve per iterate, where CG pays about two (a loose iterate and a tight one),
// and no factor is moved: S's stays, for the steps that hold nothing.
//
// A column of W is nonzero only on its unknown's elimination-tree path
// (SparseCholesky::unit_forward: a few separators on a mesh), so it costs a fraction of
// a sweep, and K_ab is the dot product over the part two paths share (from where they
// meet to the root: a suffix of both).  The columns are kept across calls while S's
// factor stays (clear() when it changes), so a contact zone that moves by a few
// unknowns a step makes a few columns a step.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <unordered_map>
#include <vector>

namespace cdyn {

class SparseCholesky;

class CapacitanceSolve {
 public:
  // Forgets the columns (S's factor has changed).
  void clear();
  // The columns of `held` (unknowns, increasing) that are not made yet, and what the
  // columns made so far cost on average (flops; 0 before the first).
  int missing(const std::vector<int>& held) const;
  double mean_column_flops() const { return columns_made_ ? column_flops_ / columns_made_ : 0.0; }
  double mean_column_length() const { return columns_made_ ? column_length_ / columns_made_ : 0.0; }
  // Makes unknown i's column (if missing): what a column costs, before pricing a set.
  void measure(const SparseCholesky& chol, int i);
  // Makes K for the unknowns `held` (increasing) from the factor `chol` of S (an LLᵀ
  // factor: SparseCholesky::has_halves), making the missing columns (nothing to do if
  // it is the last set's); returns the flops.
  // False in `ok` if K is not numerically positive definite (then solve() must not be called).
  double hold(const SparseCholesky& chol, const std::vector<int>& held, bool& ok);
  double stored_entries() const { return stored_; }  // of the columns kept (at most L's, solve_flops / 4)
  // y with y_A = b_A and S_II y_I = b_I for the held set A of the last hold().
  void solve(const SparseCholesky& chol, const Eigen::VectorXd& b, Eigen::VectorXd& y) const;
  // The same system written with the QP's own r, for the iterates of one QP, which share
  // r and differ in A and X_A = g_A: S x = r + E_A ν with K ν = g_A − Wᵀ v₀,
  // v₀ = L⁻¹ P r made once (set_rhs), so x = Pᵀ L⁻ᵀ (v₀ + W ν) costs one backward sweep
  // where solve() costs both.
  void set_rhs(const SparseCholesky& chol, const Eigen::VectorXd& r);
  void solve_held(const SparseCholesky& chol, const Eigen::VectorXd& g, Eigen::VectorXd& x) const;

 private:
  struct Column {
    std::vector<int> rows;  // of L, increasing
    std::vector<double> values;
  };
  const Column& column(const SparseCholesky& chol, int i, double& flops);  // made if missing
  void held_products(const Eigen::VectorXd& v) const;  // mu_ = Wᵀ v
  void add_held_columns() const;                       // v_ += W mu_
  std::unordered_map<int, Column> columns_;  // W's column of each unknown made so far
  double stored_ = 0.0;                      // their entries
  double column_flops_ = 0.0, column_length_ = 0.0;  // of all columns made (their means)
  int columns_made_ = 0;
  std::vector<int> held_;
  std::vector<const Column*> held_columns_;
  bool ready_ = false;  // K_ is the factor of held_'s matrix
  Eigen::LLT<Eigen::MatrixXd> K_;
  mutable Eigen::VectorXd v_, mu_;
  Eigen::VectorXd v0_;  // L⁻¹ P r of the last set_rhs
};

}  // namespace cdyn
