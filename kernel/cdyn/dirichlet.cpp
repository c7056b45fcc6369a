// dirichlet.cpp — free/fixed dof partition, lifting, restriction and extension.
#include "cdyn/dirichlet.hpp"

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

SparseMatrix DirichletLift::restrict_columns(const SparseMatrix& B) const {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(B.nonZeros());
  for (int j = 0; j < B.outerSize(); ++j) {
    if (free_index_[j] < 0) continue;
    for (SparseMatrix::InnerIterator it(B, j); it; ++it) t.emplace_back(it.row(), free_index_[j], it.value());
  }
  SparseMatrix R(B.rows(), n_free());
  R.setFromTriplets(t.begin(), t.end());
  R.makeCompressed();
  return R;
}

SparseMatrix DirichletLift::restrict(const SparseMatrix& A) const {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(A.nonZeros());
  for (int j = 0; j < A.outerSize(); ++j) {
    if (free_index_[j] < 0) continue;
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (free_index_[it.row()] >= 0) t.emplace_back(free_index_[it.row()], free_index_[j], it.value());
  }
  SparseMatrix R(n_free(), n_free());
  R.setFromTriplets(t.begin(), t.end());
  R.makeCompressed();
  return R;
}

}  // namespace cdyn
