// qp/condensation.hpp — static condensation of the unbounded unknowns with a diagonal block
// of S (the bubbles of P1+/P0), before the step QP is solved.
//
// The step QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp/bound_qp.hpp) is split into kept
// unknowns v and condensed unknowns b, where every b carries no bound and S_bb is
// diagonal.  Then the minimum over X_b is explicit,
//     X_b = S_bb⁻¹ (r_b − S_bv X_v),                                        (back-substitution)
// and X_v solves the condensed QP on the kept unknowns with the Schur complement
//     S_c = S_vv − S_vb S_bb⁻¹ S_bv,   r_c = r_v − S_vb S_bb⁻¹ r_b,   the bounds of v.   (QP_c)
// S_c is symmetric positive definite when S is, and the reaction is unchanged:
//     λ_v = (S X − r)_v = S_c X_v − r_c,   λ_b = 0,
// so (X_v, X_b) solves (QP) exactly iff X_v solves (QP_c): the two are the same problem,
// and condensed and uncondensed steps agree to round-off (tests/unit/test_condensation.cpp).
//
// Which unknowns.  Chosen from S's pattern and the bounds alone (the QP knows no mesh),
// by the rule that makes the elimination cost nothing:
//   - no bound (lower = −∞, upper = +∞) and S_bb > 0;
//   - no other condensed unknown among its neighbours in S (so S_bb is diagonal);
//   - its kept neighbours are pairwise coupled in S (a clique), so S_c has S_vv's
//     pattern: no fill, and one CHOLMOD analysis of S_c is as cheap as that of S_vv.
// Candidates are taken in order of increasing degree (fewest neighbours first), greedily.
// For P1+/P0 (seed eqs. 10–11 with H^h = P0) this picks exactly the bubbles:
// a bubble λ1λ2λ3 lives in one cell, is never constrained, couples only with the
// vertices of its cell (A_vb = 0 already, M_vb = B_Kv B_Kb / |K| through C = diag|K|),
// and those vertices are coupled to each other; an interior P1 vertex is not taken,
// its neighbours (the ring around it) are not a clique.  At n = 160 the step system
// shrinks from 76 481 to 25 281 unknowns (docs/performance.md).
//
// reduce() and expand() are gathers, one entry of the result per kept or condensed
// unknown, shared among the threads (linalg/parallel.hpp): r_c from S_bv's columns, X_b
// from S's columns b.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class DiagonalCondensation {
 public:
  // S symmetric (both triangles stored, compressed), bounds of the same size.
  DiagonalCondensation(const SparseMatrix& S, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);

  int n() const { return static_cast<int>(kept_of_.size()); }        // all unknowns
  int n_kept() const { return static_cast<int>(kept_.size()); }
  int n_condensed() const { return static_cast<int>(condensed_.size()); }
  bool condenses(int i) const { return kept_of_[i] < 0; }

  // The full S it was built from, and S_c = S_vv − S_vb S_bb⁻¹ S_bv (symmetric, both
  // triangles, compressed).
  const SparseMatrix& S() const { return S_; }
  const SparseMatrix& S_c() const { return S_c_; }
  // x_v: the kept entries of a vector on all unknowns (bounds, a warm start).
  Eigen::VectorXd kept(const Eigen::VectorXd& x) const;
  // r_c = r_v − S_vb S_bb⁻¹ r_b.
  Eigen::VectorXd reduce(const Eigen::VectorXd& r) const;
  // X on all unknowns from X_v: X_b = S_bb⁻¹ (r_b − S_bv X_v).
  Eigen::VectorXd expand(const Eigen::VectorXd& X_v, const Eigen::VectorXd& r) const;
  // λ on all unknowns from λ_v (λ_b = 0 by the back-substitution).
  Eigen::VectorXd expand_reaction(const Eigen::VectorXd& lambda_v) const;

 private:
  SparseMatrix S_;                 // the full S (its columns b are read by expand)
  SparseMatrix S_bv_;              // S_bv: column j lists the condensed neighbours of kept j (reduce)
  SparseMatrix S_c_;
  std::vector<int> kept_, condensed_;  // unknown indices
  std::vector<int> kept_of_;       // unknown → index among kept, or −1 when condensed
  Eigen::VectorXd S_bb_;           // diagonal of S on the condensed unknowns
};

}  // namespace cdyn
