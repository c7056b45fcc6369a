// qp/condensation.cpp — S_c = S_vv − S_vb S_bb⁻¹ S_bv and the back-substitution; see
// qp/condensation.hpp.
#include "cdyn/qp/condensation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <Eigen/Cholesky>

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

// M.reserve(count), but not for a matrix with no columns (everything condensed, as the
// one unknown of an oscillator): reserve() would leave it uncompressed, and Eigen's
// makeCompressed() then reads past the outer index of no columns.
void reserve_per_column(SparseMatrix& M, const std::vector<int>& count) {
  if (!count.empty()) M.reserve(count);
}

// S_vv: the rows and columns of S on the kept unknowns (increasing), compressed.
SparseMatrix kept_block(const SparseMatrix& S, const std::vector<int>& kept, const std::vector<int>& kept_of) {
  const int n_kept = static_cast<int>(kept.size());
  SparseMatrix S_vv(n_kept, n_kept);
  std::vector<int> count(n_kept, 0);
  for (int j = 0; j < n_kept; ++j)
    for (SparseMatrix::InnerIterator it(S, kept[j]); it; ++it) count[j] += kept_of[it.row()] >= 0;
  reserve_per_column(S_vv, count);
  for (int j = 0; j < n_kept; ++j)  // rows in increasing order: kept_of is increasing
    for (SparseMatrix::InnerIterator it(S, kept[j]); it; ++it)
      if (kept_of[it.row()] >= 0) S_vv.insert(kept_of[it.row()], j) = it.value();
  S_vv.makeCompressed();
  return S_vv;
}

// S_GG: the dense block of S on the unknowns G.
Eigen::MatrixXd block_of(const SparseMatrix& S, const std::vector<int>& G) {
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(G.size()), static_cast<Eigen::Index>(G.size()));
  for (std::size_t q = 0; q < G.size(); ++q)
    for (SparseMatrix::InnerIterator it(S, G[q]); it; ++it) {
      const auto p = std::find(G.begin(), G.end(), static_cast<int>(it.row()));
      if (p != G.end()) block(p - G.begin(), static_cast<Eigen::Index>(q)) = it.value();
    }
  return block;
}

}  // namespace

StaticCondensation::StaticCondensation(const SparseMatrix& S, const Eigen::VectorXd& lower,
                                       const Eigen::VectorXd& upper, const std::vector<std::vector<int>>& blocks,
                                       bool single_unknowns)
    : S_(S) {
  S_.makeCompressed();
  const int n = static_cast<int>(S_.rows());
  if (S_.cols() != n || lower.size() != n || upper.size() != n)
    throw InputError("condensation: S and the bounds have different sizes");

  std::vector<int> degree(n, 0);
  std::vector<double> diagonal(n, 0.0);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(S_, j); it; ++it) {
      if (it.row() == j)
        diagonal[j] = it.value();
      else
        ++degree[j];
    }
  auto candidate = [&](int j) {
    return lower[j] == -INFINITY && upper[j] == INFINITY && diagonal[j] > 0 && degree[j] <= kMaxDegree;
  };

  // Condenses the unknowns of G together when the rules of the header allow it.
  std::vector<char> condensed(n, 0), in_block(n, 0), seen(n, 0);
  std::vector<std::vector<int>> chosen;
  std::vector<int> neighbours;
  auto try_condense = [&](std::vector<int> G) {
    for (int b : G)
      if (!candidate(b) || condensed[b]) return;
    for (int b : G) in_block[b] = 1;
    neighbours.clear();
    bool ok = true;
    for (std::size_t m = 0; ok && m < G.size(); ++m)
      for (SparseMatrix::InnerIterator it(S_, G[m]); it && ok; ++it) {
        const int i = static_cast<int>(it.row());
        if (in_block[i] || seen[i]) continue;
        ok = !condensed[i];  // S_bb stays block diagonal
        seen[i] = 1;
        neighbours.push_back(i);
      }
    for (int i : neighbours) seen[i] = 0;
    for (int b : G) in_block[b] = 0;
    // no fill: the kept neighbours are already coupled
    for (std::size_t p = 0; ok && p < neighbours.size(); ++p)
      for (std::size_t q = p + 1; ok && q < neighbours.size(); ++q) ok = stored(S_, neighbours[p], neighbours[q]);
    if (ok && G.size() > 1) ok = block_of(S_, G).llt().info() == Eigen::Success;  // S_bb > 0
    if (!ok) return;
    std::sort(G.begin(), G.end());
    for (int b : G) condensed[b] = 1;
    chosen.push_back(std::move(G));
  };

  std::vector<char> named(n, 0);
  for (const std::vector<int>& G : blocks) {
    if (G.empty() || static_cast<int>(G.size()) > kMaxBlock)
      throw InputError("condensation: a block has " + std::to_string(G.size()) + " unknowns (1 to " +
                       std::to_string(kMaxBlock) + ")");
    for (int b : G) {
      if (b < 0 || b >= n) throw InputError("condensation: a block names unknown " + std::to_string(b));
      if (named[b]) throw InputError("condensation: unknown " + std::to_string(b) + " is in two blocks");
      named[b] = 1;
    }
    try_condense(G);
  }
  // then single unknowns, fewest neighbours first
  std::vector<int> singles;
  for (int j = 0; j < n && single_unknowns; ++j)
    if (candidate(j) && !condensed[j]) singles.push_back(j);
  std::stable_sort(singles.begin(), singles.end(), [&](int a, int b) { return degree[a] < degree[b]; });
  for (int b : singles) try_condense({b});

  // the blocks in the order of their first unknowns (single unknowns: increasing index)
  std::sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a[0] < b[0]; });
  for (const std::vector<int>& G : chosen) {
    first_.push_back(n_condensed());
    condensed_.insert(condensed_.end(), G.begin(), G.end());
    inverse_at_.push_back(static_cast<int>(inverse_.size()));
    if (G.size() == 1) {
      inverse_.push_back(diagonal[G[0]]);
    } else {
      const Eigen::MatrixXd inverse = block_of(S_, G).llt().solve(Eigen::MatrixXd::Identity(G.size(), G.size()));
      inverse_.insert(inverse_.end(), inverse.data(), inverse.data() + inverse.size());
    }
  }
  first_.push_back(n_condensed());
  kept_of_.assign(n, -1);
  for (int i = 0; i < n; ++i)
    if (!condensed[i]) {
      kept_of_[i] = static_cast<int>(kept_.size());
      kept_.push_back(i);
    }

  // S_c: the kept block S_vv, then −S_vg S_gg⁻¹ S_gv for each condensed block g, added in
  // place: S_c has S_vv's pattern (no fill), so no list of entries is made (in 3D a
  // block's 12 kept neighbours give 144 entries: 28M at n = 32).
  S_c_ = kept_block(S_, kept_, kept_of_);
  // S_c(i, j) += u for kept unknowns i, j (in S's numbering), and S_c(j, i) too: both
  // triangles get the same sums in the same order (S_c exactly symmetric)
  auto add = [&](int i, int j, double u) {
    const int ki = kept_of_[i], kj = kept_of_[j];
    S_c_.coeffRef(ki, kj) += u;
    if (ki != kj) S_c_.coeffRef(kj, ki) += u;
  };
  for (int g = 0; g + 1 < static_cast<int>(first_.size()); ++g) {
    const int m = first_[g + 1] - first_[g];
    const int* members = condensed_.data() + first_[g];
    // the block's kept neighbours and S_vg (rows: neighbours, columns: the block's unknowns)
    neighbours.clear();
    for (int p = 0; p < m; ++p)
      for (SparseMatrix::InnerIterator it(S_, members[p]); it; ++it)
        if (kept_of_[it.row()] >= 0) neighbours.push_back(static_cast<int>(it.row()));
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    const int nn = static_cast<int>(neighbours.size());
    Eigen::MatrixXd S_vg = Eigen::MatrixXd::Zero(nn, m);
    for (int p = 0; p < m; ++p)
      for (SparseMatrix::InnerIterator it(S_, members[p]); it; ++it)
        if (kept_of_[it.row()] >= 0) {
          const auto i = std::lower_bound(neighbours.begin(), neighbours.end(), static_cast<int>(it.row()));
          S_vg(i - neighbours.begin(), p) = it.value();
        }
    const Eigen::Map<const Eigen::MatrixXd> inverse(inverse_.data() + inverse_at_[g], m, m);
    const Eigen::MatrixXd Y = m == 1 ? Eigen::MatrixXd(S_vg / inverse(0, 0)) : Eigen::MatrixXd(S_vg * inverse);
    for (int q = 0; q < nn; ++q)
      for (int p = 0; p <= q; ++p) add(neighbours[p], neighbours[q], -Y.row(p).dot(S_vg.row(q)));
  }

  // S_bv: column j lists the condensed neighbours k of kept j (S's column j, its rows b
  // renumbered by their place in condensed_, sorted)
  std::vector<int> place(n, -1);
  for (int k = 0; k < n_condensed(); ++k) place[condensed_[k]] = k;
  S_bv_ = SparseMatrix(n_condensed(), n_kept());
  std::vector<int> count(n_kept(), 0);
  for (int j = 0; j < n_kept(); ++j)
    for (SparseMatrix::InnerIterator it(S_, kept_[j]); it; ++it) count[j] += place[it.row()] >= 0;
  reserve_per_column(S_bv_, count);
  std::vector<std::pair<int, double>> column;
  for (int j = 0; j < n_kept(); ++j) {
    column.clear();
    for (SparseMatrix::InnerIterator it(S_, kept_[j]); it; ++it)
      if (place[it.row()] >= 0) column.emplace_back(place[it.row()], it.value());
    std::sort(column.begin(), column.end());
    for (const auto& [k, v] : column) S_bv_.insert(k, j) = v;
  }
  S_bv_.makeCompressed();
}

void StaticCondensation::solve_block(int g, double* y) const {
  const int m = first_[g + 1] - first_[g];
  const double* inverse = inverse_.data() + inverse_at_[g];
  if (m == 1) {
    y[0] /= inverse[0];  // S_bb
    return;
  }
  double z[kMaxBlock];
  for (int p = 0; p < m; ++p) z[p] = y[p];
  for (int p = 0; p < m; ++p) {
    double s = 0.0;
    for (int q = 0; q < m; ++q) s += inverse[p + m * q] * z[q];
    y[p] = s;
  }
}

Eigen::VectorXd StaticCondensation::kept(const Eigen::VectorXd& x) const {
  Eigen::VectorXd out(n_kept());
#pragma omp parallel for schedule(static) if (n_kept() >= kParallelWork)
  for (int k = 0; k < n_kept(); ++k) out[k] = x[kept_[k]];
  return out;
}

// r_c,j = r_j − Σ_b S_jb y_b with y = S_bb⁻¹ r_b, the terms subtracted one by one in
// the order of b.
Eigen::VectorXd StaticCondensation::reduce(const Eigen::VectorXd& r) const {
  // (the blocks are independent: shared among the threads, each solved as on one)
  Eigen::VectorXd y(n_condensed());
  const int n_blocks = static_cast<int>(first_.size()) - 1;
#pragma omp parallel for schedule(static) if (n_condensed() >= kParallelWork)
  for (int g = 0; g < n_blocks; ++g) {
    for (int k = first_[g]; k < first_[g + 1]; ++k) y[k] = r[condensed_[k]];
    solve_block(g, y.data() + first_[g]);
  }
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

Eigen::VectorXd StaticCondensation::expand(const Eigen::VectorXd& X_v, const Eigen::VectorXd& r) const {
  Eigen::VectorXd X(n());
#pragma omp parallel for schedule(static) if (n_kept() >= kParallelWork)
  for (int k = 0; k < n_kept(); ++k) X[kept_[k]] = X_v[k];
  const int n_blocks = static_cast<int>(first_.size()) - 1;
#pragma omp parallel for schedule(static) if (S_bv_.nonZeros() >= kParallelWork)
  for (int g = 0; g < n_blocks; ++g) {
    double y[kMaxBlock];
    for (int k = first_[g]; k < first_[g + 1]; ++k) {
      const int b = condensed_[k];
      double rb = r[b];
      for (SparseMatrix::InnerIterator it(S_, b); it; ++it)
        if (kept_of_[it.row()] >= 0) rb -= it.value() * X_v[kept_of_[it.row()]];
      y[k - first_[g]] = rb;
    }
    solve_block(g, y);
    for (int k = first_[g]; k < first_[g + 1]; ++k) X[condensed_[k]] = y[k - first_[g]];
  }
  return X;
}

Eigen::VectorXd StaticCondensation::expand_reaction(const Eigen::VectorXd& lambda_v) const {
  Eigen::VectorXd lambda(n());
#pragma omp parallel for schedule(static) if (n() >= kParallelWork)
  for (int i = 0; i < n(); ++i) lambda[i] = 0.0;
#pragma omp parallel for schedule(static) if (n_kept() >= kParallelWork)
  for (int k = 0; k < n_kept(); ++k) lambda[kept_[k]] = lambda_v[k];
  return lambda;
}

}  // namespace cdyn
