// free_block_factor.cpp — the block I⁺ = I ∪ M of S̃, its factor and its row updates; see
// qp/pdas/free_block_factor.hpp.
#include "cdyn/qp/pdas/free_block_factor.hpp"

namespace cdyn {

void FreeBlockFactor::make(const SparseMatrix& S, const HeldSet& held, const SparseCholesky& whole,
                           PDASCounters& counters) {
  const int n = static_cast<int>(held.size());
  std::vector<char> in_block(n, 0);
  for (int i = 0; i < n; ++i)
    if (!held[i])
      for (SparseMatrix::InnerIterator it(S, i); it; ++it) in_block[it.row()] = 1;  // (S symmetric: i's neighbours)
  index_.assign(n, -1);
  block_.clear();
  held_.clear();
  for (int i = 0; i < n; ++i)
    if (in_block[i]) {
      index_[i] = static_cast<int>(block_.size());
      block_.push_back(i);
      held_.push_back(held[i]);
    }
  // S on I⁺, its columns sorted (I⁺ increasing)
  const int m = static_cast<int>(block_.size());
  std::vector<int> outer(m + 1, 0), inner;
  std::vector<double> value;
  for (int k = 0; k < m; ++k) {
    for (SparseMatrix::InnerIterator it(S, block_[k]); it; ++it)
      if (index_[it.row()] >= 0) {
        inner.push_back(index_[it.row()]);
        value.push_back(it.value());
      }
    outer[k + 1] = static_cast<int>(inner.size());
  }
  S_ = Eigen::Map<const SparseMatrix>(m, m, static_cast<int>(inner.size()), outer.data(), inner.data(), value.data());
  S_.makeCompressed();
  if (m == 0) return;  // every unknown held: X = b̃ (solve)
  if (!chol_.analyzed_for(S_)) {
    std::vector<int> ordering;  // I⁺ in the order S eliminates it
    ordering.reserve(m);
    for (int i : whole.ordering())
      if (index_[i] >= 0) ordering.push_back(index_[i]);
    chol_.analyze(S_, ordering);
    ++counters.analyses;
  }
  SparseMatrix S_tilde = S_;  // (replace_held_by_identity writes the values of S_'s pattern)
  replace_held_by_identity(S_, held_, S_tilde);
  factorize_counted(chol_, S_tilde, "the reduced matrix S_II is not positive definite (breakdown", counters, &block_);
}

Eigen::VectorXd FreeBlockFactor::solve(const Eigen::VectorXd& b) const {
  if (block_.empty()) return b;
  Eigen::VectorXd b_block(block_.size());
  for (std::size_t k = 0; k < block_.size(); ++k) b_block[k] = b[block_[k]];
  const Eigen::VectorXd y_block = chol_.solve(b_block);
  Eigen::VectorXd y = b;
  for (std::size_t k = 0; k < block_.size(); ++k) y[block_[k]] = y_block[k];
  return y;
}

bool FreeBlockFactor::updates_pay(const HeldSet& from, const HeldSet& held, int limit) const {
  if (block_.empty()) return false;
  int changes = 0;
  for (std::size_t i = 0; i < held.size(); ++i)
    if (held[i] != from[i]) {
      if (index_[i] < 0) return false;  // beyond the margin: a new block
      ++changes;
    }
  if (!updates_measured()) return changes <= limit;
  return changes * update_flops() < 0.5 * factorization_flops();
}

bool FreeBlockFactor::update(const std::vector<int>& to_delete, const std::vector<int>& to_add) {
  auto in_block = [this](const std::vector<int>& unknowns) {
    std::vector<int> k;
    for (int i : unknowns) k.push_back(index_[i]);
    return k;
  };
  if (!update_held(chol_, S_, held_, in_block(to_delete), in_block(to_add), update_flops_)) return false;
  updates_measured_ += static_cast<int>(to_delete.size() + to_add.size());
  return true;
}

}  // namespace cdyn
