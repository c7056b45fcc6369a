// free_block_factor.hpp — the factor of the reduced system S̃ on the free unknowns and
// their held neighbours alone: what ExplicitReducedSystem factorizes, instead of S̃ in
// S's whole pattern, for an active set that holds most unknowns (resting contact: a body
// lying on the obstacle; explicit_reduced_system.hpp, QPOptions::pdas_free_block).
//
// S̃ in S's pattern keeps the fill of the whole S, while the free block is much smaller.
// The block is S̃ on I⁺ = I ∪ M, M the held neighbours of the free unknowns I (their rows
// the identity's), in the order S's own analysis eliminates I⁺ (a principal submatrix of
// a well-ordered S fills about as little, and a minimum degree search of its own cost as
// much as the numeric factorization), analysed once per I⁺.  The margin M costs one ring
// of unknowns around I and lets the unknowns that switch within I⁺ be row updates on the
// factor: measured on the resting membrane at n = 640, the PDAS iterations after each new
// block flipped 2–16 vertices at the lift-off front, each flip a new analysis and
// factorization of a block without the margin (docs/performance.md, (c)).
#pragma once

#include <vector>

#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/qp/pdas/reduced_system.hpp"

namespace cdyn {

class FreeBlockFactor {
 public:
  // The block of `held` in S (symmetric, compressed), factorized (analysed in the order of
  // `whole`, S's own analysis, when I⁺ changed); NumericalError if it is not positive
  // definite.
  void make(const SparseMatrix& S, const HeldSet& held, const SparseCholesky& whole, PDASCounters& counters);
  // S̃ y = b: y = b outside I⁺, and on I⁺ the block's S̃ (whose held rows give y_A = b_A).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

  // Whether the factor, made for `from`, is brought to `held` by row updates: every
  // changed unknown in I⁺, and their flops under half a factorization's (as for S̃'s
  // factor); before any is measured, at most `limit` of them, to measure them.
  bool updates_pay(const HeldSet& from, const HeldSet& held, int limit) const;
  // Those row updates (unknowns in S's numbering); false when the result is found not
  // positive definite (round-off: a new block is due).
  bool update(const std::vector<int>& to_delete, const std::vector<int>& to_add);
  bool updates_measured() const { return updates_measured_ > 0; }
  double update_flops() const { return update_flops_ / updates_measured_; }  // their mean (requires one)
  double factorization_flops() const { return chol_.factorization_flops(); }
  double solve_flops() const { return chol_.solve_flops(); }

 private:
  std::vector<int> block_;  // I⁺ (increasing)
  std::vector<int> index_;  // an unknown's position in block_, −1 outside
  HeldSet held_;            // the held ones of block_ (M, and I's since held)
  SparseMatrix S_;          // S restricted to I⁺ (its values as in S: update_held's restores)
  SparseCholesky chol_;
  double update_flops_ = 0.0;  // the row updates on block factors so far
  int updates_measured_ = 0;
};

}  // namespace cdyn
