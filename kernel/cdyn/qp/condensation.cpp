// qp/condensation.cpp — S_c = S_vv − S_vb S_bb⁻¹ S_bv and the back-substitution; see
// qp/condensation.hpp.
#include "cdyn/qp/condensation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

namespace {

// Is (i, j) stored in S?  Binary search in column j (rows are sorted in compressed form).
bool stored(const SparseMatrix& S, int i, int j) {
  const int* begin = S.innerIndexPtr() + S.outerIndexPtr()[j];
  const int* end = S.innerIndexPtr() + S.outerIndexPtr()[j + 1];
  return std::binary_search(begin, end, i);
}

// Beyond this many neighbours the clique test (quadratic in the degree) is not tried:
// such an unknown is not a bubble, and eliminating it would not pay.
constexpr int kMaxDegree = 32;

}  // namespace

DiagonalCondensation::DiagonalCondensation(const SparseMatrix& S, const Eigen::VectorXd& lower,
                                           const Eigen::VectorXd& upper)
    : S_(S) {
  S_.makeCompressed();
  const int n = static_cast<int>(S_.rows());
  if (S_.cols() != n || lower.size() != n || upper.size() != n)
    throw InputError("condensation: S and the bounds have different sizes");

  // Candidates: unbounded, positive diagonal, small degree; fewest neighbours first.
  std::vector<int> degree(n, 0);
  std::vector<double> diagonal(n, 0.0);
  std::vector<int> candidates;
  for (int j = 0; j < n; ++j) {
    for (SparseMatrix::InnerIterator it(S_, j); it; ++it) {
      if (it.row() == j)
        diagonal[j] = it.value();
      else
        ++degree[j];
    }
    if (lower[j] == -INFINITY && upper[j] == INFINITY && diagonal[j] > 0 && degree[j] <= kMaxDegree)
      candidates.push_back(j);
  }
  std::stable_sort(candidates.begin(), candidates.end(), [&](int a, int b) { return degree[a] < degree[b]; });

  std::vector<char> condensed(n, 0);
  std::vector<int> neighbours;
  for (int b : candidates) {
    neighbours.clear();
    bool ok = true;
    for (SparseMatrix::InnerIterator it(S_, b); it && ok; ++it) {
      const int i = static_cast<int>(it.row());
      if (i == b) continue;
      ok = !condensed[i];  // S_bb stays diagonal
      neighbours.push_back(i);
    }
    for (std::size_t p = 0; ok && p < neighbours.size(); ++p)
      for (std::size_t q = p + 1; ok && q < neighbours.size(); ++q) ok = stored(S_, neighbours[p], neighbours[q]);
    if (ok) condensed[b] = 1;  // no fill: the kept neighbours are already coupled
  }

  kept_of_.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    if (condensed[i]) {
      condensed_.push_back(i);
    } else {
      kept_of_[i] = static_cast<int>(kept_.size());
      kept_.push_back(i);
    }
  }
  S_bb_.resize(n_condensed());
  for (int k = 0; k < n_condensed(); ++k) S_bb_[k] = diagonal[condensed_[k]];

  // S_c: the kept block, then −S_ib S_jb / S_bb for each condensed b and kept i, j.
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(S_.nonZeros());
  for (int j : kept_)
    for (SparseMatrix::InnerIterator it(S_, j); it; ++it)
      if (kept_of_[it.row()] >= 0) t.emplace_back(kept_of_[it.row()], kept_of_[j], it.value());
  for (int k = 0; k < n_condensed(); ++k) {
    const int b = condensed_[k];
    for (SparseMatrix::InnerIterator it(S_, b); it; ++it) {
      if (it.row() == b) continue;
      for (SparseMatrix::InnerIterator jt(S_, b); jt; ++jt) {
        if (jt.row() == b) continue;
        t.emplace_back(kept_of_[it.row()], kept_of_[jt.row()], -it.value() * jt.value() / S_bb_[k]);
      }
    }
  }
  S_c_.resize(n_kept(), n_kept());
  S_c_.setFromTriplets(t.begin(), t.end());
  // exact symmetry (duplicates are summed in different orders in the two triangles)
  S_c_ = 0.5 * (S_c_ + SparseMatrix(S_c_.transpose()));
  S_c_.makeCompressed();

  // S_bv from S's columns b: for each kept j, its entries S_jb in the order of b
  std::vector<Eigen::Triplet<double>> bv;
  for (int k = 0; k < n_condensed(); ++k)
    for (SparseMatrix::InnerIterator it(S_, condensed_[k]); it; ++it)
      if (it.row() != condensed_[k]) bv.emplace_back(k, kept_of_[it.row()], it.value());
  S_bv_.resize(n_condensed(), n_kept());
  S_bv_.setFromTriplets(bv.begin(), bv.end());
  S_bv_.makeCompressed();
}

Eigen::VectorXd DiagonalCondensation::kept(const Eigen::VectorXd& x) const {
  Eigen::VectorXd out(n_kept());
#pragma omp parallel for schedule(static) if (n_kept() >= kParallelWork)
  for (int k = 0; k < n_kept(); ++k) out[k] = x[kept_[k]];
  return out;
}

// r_c,j = r_j − Σ_b S_jb y_b with y_b = r_b / S_bb, the terms subtracted one by one in
// the order of b.
Eigen::VectorXd DiagonalCondensation::reduce(const Eigen::VectorXd& r) const {
  Eigen::VectorXd y(n_condensed());
  for (int k = 0; k < n_condensed(); ++k) y[k] = r[condensed_[k]] / S_bb_[k];
  const int* outer = S_bv_.outerIndexPtr();
  const int* inner = S_bv_.innerIndexPtr();
  const double* v = S_bv_.valuePtr();
  Eigen::VectorXd rc(n_kept());
#pragma omp parallel for schedule(static) if (S_bv_.nonZeros() >= kParallelWork)
  for (int j = 0; j < n_kept(); ++j) {
    double s = r[kept_[j]];
    for (int p = outer[j]; p < outer[j + 1]; ++p) s -= v[p] * y[inner[p]];
    rc[j] = s;
  }
  return rc;
}

Eigen::VectorXd DiagonalCondensation::expand(const Eigen::VectorXd& X_v, const Eigen::VectorXd& r) const {
  Eigen::VectorXd X(n());
  for (int k = 0; k < n_kept(); ++k) X[kept_[k]] = X_v[k];
#pragma omp parallel for schedule(static) if (S_bv_.nonZeros() >= kParallelWork)
  for (int k = 0; k < n_condensed(); ++k) {
    const int b = condensed_[k];
    double rb = r[b];
    for (SparseMatrix::InnerIterator it(S_, b); it; ++it)
      if (it.row() != b) rb -= it.value() * X_v[kept_of_[it.row()]];
    X[b] = rb / S_bb_[k];
  }
  return X;
}

Eigen::VectorXd DiagonalCondensation::expand_reaction(const Eigen::VectorXd& lambda_v) const {
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(n());
  for (int k = 0; k < n_kept(); ++k) lambda[kept_[k]] = lambda_v[k];
  return lambda;
}

}  // namespace cdyn
