// reference_pdas.cpp — textbook primal-dual active set iteration (Hintermüller, Ito &
// Kunisch 2002), every free block factorized from scratch; see reference_pdas.hpp.
#include "cdyn/qp/pdas/reference_pdas.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <chrono>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"

namespace cdyn {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Appends factor × M(rows, cols) to t, the entries of M whose row i has row_at[i] ≥ 0
// and column j col_at[j] ≥ 0, at (row_at[i] + row_offset, col_at[j] + col_offset).
void append_block(const SparseMatrix& M, const std::vector<int>& row_at, const std::vector<int>& col_at,
                  int row_offset, int col_offset, double factor, Triplets& t) {
  for (int j = 0; j < M.outerSize(); ++j)
    if (col_at[j] >= 0)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it)
        if (row_at[it.row()] >= 0)
          t.emplace_back(row_at[it.row()] + row_offset, col_at[j] + col_offset, factor * it.value());
}

// X with X_A = held_values_A and S_II X_I = r_I − S_IA X_A; at[i] is i's position in I
// (−1 on A), held_values is 0 on I.
Eigen::VectorXd solve_free_block(const BoundQP& qp, const std::vector<int>& at, int n_free,
                                 const Eigen::VectorXd& held_values) {
  const int n = qp.size();
  Eigen::VectorXd X = held_values;
  if (n_free == 0) return X;
  Eigen::VectorXd x_free;
  Triplets t;
  if (!qp.saddle) {
    const Eigen::VectorXd rhs = qp.r - qp.S * held_values;
    append_block(qp.S, at, at, 0, 0, 1.0, t);
    SparseMatrix S_II(n_free, n_free);
    S_II.setFromTriplets(t.begin(), t.end());
    Eigen::VectorXd b(n_free);
    for (int i = 0; i < n; ++i)
      if (at[i] >= 0) b[at[i]] = rhs[i];
    Eigen::SimplicialLDLT<SparseMatrix> ldlt(S_II);
    if (ldlt.info() != Eigen::Success) throw NumericalError("reference_pdas: S_II could not be factorized");
    x_free = ldlt.solve(b);
  } else {
    // [[A_II, c B_Iᵀ], [B_I, −C]] [X_I; Z] = [r_I − A_IA X_A; −B_A X_A]  (Z = C⁻¹ B X)
    const SaddleForm& f = *qp.saddle;
    const int m = static_cast<int>(f.C.rows());
    std::vector<int> all(m);
    for (int k = 0; k < m; ++k) all[k] = k;
    append_block(f.A, at, at, 0, 0, 1.0, t);
    append_block(f.B, all, at, n_free, 0, 1.0, t);
    const SparseMatrix Bt = f.B.transpose();
    append_block(Bt, at, all, 0, n_free, f.c, t);
    append_block(f.C, all, all, n_free, n_free, -1.0, t);
    SparseMatrix K(n_free + m, n_free + m);
    K.setFromTriplets(t.begin(), t.end());
    K.makeCompressed();
    const Eigen::VectorXd top = qp.r - f.A * held_values;
    Eigen::VectorXd b(n_free + m);
    for (int i = 0; i < n; ++i)
      if (at[i] >= 0) b[at[i]] = top[i];
    b.tail(m) = -(f.B * held_values);
    Eigen::SparseLU<SparseMatrix> lu(K);
    if (lu.info() != Eigen::Success) throw NumericalError("reference_pdas: the reduced saddle matrix is singular");
    // The blocks differ in size by c (1/dt² and more): two steps of iterative refinement
    // of the linear solve bring it to round-off, as UMFPACK does by default.
    Eigen::VectorXd y = lu.solve(b);
    for (int k = 0; k < 2; ++k) y += lu.solve(b - K * y);
    x_free = y.head(n_free);
  }
  for (int i = 0; i < n; ++i)
    if (at[i] >= 0) X[i] = x_free[at[i]];
  return X;
}

}  // namespace

ReferencePDASSolver::ReferencePDASSolver(const QPOptions& options) : options_(options) {
  if (options_.max_iterations == 0) options_.max_iterations = 100;
}

QPResult ReferencePDASSolver::solve(const BoundQP& qp, const QPResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  check_problem(qp);
  const int n = qp.size();
  const Eigen::VectorXd& l = qp.lower;
  const Eigen::VectorXd& u = qp.upper;
  QuadraticForm form;
  form.set(qp);
  const Eigen::VectorXd& D = form.diagonal();
  // The active set as the bound each unknown is held at: −1 lower, +1 upper, 0 free.
  std::vector<int> bound(n, 0);
  for (int i = 0; i < n; ++i)
    if (l[i] == u[i]) bound[i] = -1;
  if (warm_start && warm_start->X.size() == n)
    for (int i : warm_start->active)
      if (i >= 0 && i < n && bound[i] == 0) {
        const double x = warm_start->X[i];
        bound[i] = std::isfinite(l[i]) && (!std::isfinite(u[i]) || x - l[i] <= u[i] - x) ? -1 : 1;
      }

  QPResult result;
  result.X = Eigen::VectorXd::Zero(n);
  bool repeated = n == 0;
  while (!repeated && result.iterations < options_.max_iterations) {
    ++result.iterations;
    std::vector<int> at(n, -1);
    int n_free = 0;
    Eigen::VectorXd held_values = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      if (bound[i] == 0) at[i] = n_free++;
      if (bound[i] < 0) held_values[i] = l[i];
      if (bound[i] > 0) held_values[i] = u[i];
    }
    result.X = solve_free_block(qp, at, n_free, held_values);
    const Eigen::VectorXd lam = form.gradient(result.X);
    std::vector<int> next(n, 0);
    for (int i = 0; i < n; ++i) {
      const double x = result.X[i];
      if (l[i] == u[i] || (std::isfinite(l[i]) && lam[i] + D[i] * (l[i] - x) > 0))
        next[i] = -1;
      else if (std::isfinite(u[i]) && lam[i] + D[i] * (u[i] - x) < 0)
        next[i] = 1;
    }
    repeated = next == bound;
    bound = std::move(next);
  }
  finish_result(qp, form, options_.tol, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_failure("reference_pdas", options_, result, repeated ? "" : "the active set did not repeat");
  return result;
}

}  // namespace cdyn
