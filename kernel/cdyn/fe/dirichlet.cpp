// fe/dirichlet.cpp — free/fixed dof partition, lifting, restriction and extension.
#include "cdyn/fe/dirichlet.hpp"

#include <algorithm>

namespace cdyn {

DirichletLift::DirichletLift(const FESpace& W, const std::vector<int>& parts, std::vector<int> components) {
  if (components.empty())
    for (int k = 0; k < W.components(); ++k) components.push_back(k);
  std::vector<char> fixed(W.n_dofs(), 0);
  for (int s : W.boundary_scalar_dofs(parts))
    for (int k : components) fixed[W.dof(s, k)] = 1;
  free_index_.assign(W.n_dofs(), -1);
  for (int i = 0; i < W.n_dofs(); ++i) {
    if (fixed[i]) {
      fixed_.push_back(i);
    } else {
      free_index_[i] = static_cast<int>(free_.size());
      free_.push_back(i);
    }
  }
}

Eigen::VectorXd DirichletLift::lifting(const FESpace& W, const std::vector<Field>& g, double t) const {
  // Interpolating g on the whole space and keeping the fixed entries gives the right
  // boundary values (vertex and edge dofs are nodal); interior entries are zeroed.
  const Eigen::VectorXd G = W.interpolate(g, t);
  Eigen::VectorXd UD = Eigen::VectorXd::Zero(W.n_dofs());
  for (int i : fixed_) UD[i] = G[i];
  return UD;
}

Eigen::VectorXd DirichletLift::restrict(const Eigen::VectorXd& U) const {
  Eigen::VectorXd Uf(n_free());
  for (int j = 0; j < n_free(); ++j) Uf[j] = U[free_[j]];
  return Uf;
}

Eigen::VectorXd DirichletLift::extend(const Eigen::VectorXd& Uf, const Eigen::VectorXd& UD) const {
  Eigen::VectorXd U = UD;
  for (int j = 0; j < n_free(); ++j) U[free_[j]] = Uf[j];
  return U;
}

SparseMatrix submatrix(const SparseMatrix& S, const std::vector<int>& row_index, int n_rows,
                       const std::vector<int>& col_index, int n_cols) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(S.nonZeros());
  for (int j = 0; j < S.outerSize(); ++j) {
    if (col_index[j] < 0) continue;
    for (SparseMatrix::InnerIterator it(S, j); it; ++it)
      if (row_index[it.row()] >= 0) t.emplace_back(row_index[it.row()], col_index[j], it.value());
  }
  SparseMatrix R(n_rows, n_cols);
  R.setFromTriplets(t.begin(), t.end());
  R.makeCompressed();
  return R;
}

SparseMatrix DirichletLift::restrict_columns(const SparseMatrix& B) const {
  std::vector<int> all_rows(B.rows());
  for (int i = 0; i < B.rows(); ++i) all_rows[i] = i;
  return submatrix(B, all_rows, static_cast<int>(B.rows()), free_index_, n_free());
}

SparseMatrix DirichletLift::restrict(const SparseMatrix& A) const {
  return submatrix(A, free_index_, n_free(), free_index_, n_free());
}

}  // namespace cdyn
