// qp/condensation.hpp — static condensation of the unbounded unknowns whose block of S
// is block diagonal (the bubbles of P1+/P0), before the step QP is solved.
//
// The step QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp/bound_qp.hpp) is split into kept
// unknowns v and condensed unknowns b, where every b carries no bound and S_bb is
// block diagonal with small blocks.  Then the minimum over X_b is explicit,
//     X_b = S_bb⁻¹ (r_b − S_bv X_v),                                        (back-substitution)
// and X_v solves the condensed QP on the kept unknowns with the Schur complement
//     S_c = S_vv − S_vb S_bb⁻¹ S_bv,   r_c = r_v − S_vb S_bb⁻¹ r_b,   the bounds of v.   (QP_c)
// S_c is symmetric positive definite when S is, and the reaction is unchanged:
//     λ_v = (S X − r)_v = S_c X_v − r_c,   λ_b = 0,
// so (X_v, X_b) solves (QP) exactly iff X_v solves (QP_c): the two are the same problem,
// and condensed and uncondensed steps agree to round-off (tests/unit/test_condensation.cpp).
//
// Which unknowns.  Those of the blocks the caller names (the step's scheme names each
// cell's bubble, one unknown per component: the QP itself knows no mesh), then single
// unknowns found from S's pattern; a block or a single unknown b is condensed when
//   - none of its unknowns has a bound (lower = −∞, upper = +∞), and S_bb is positive
//     definite;
//   - no unknown of another condensed block is among its neighbours (S_bb stays block
//     diagonal);
//   - its kept neighbours are pairwise coupled in S (a clique), so S_c has S_vv's
//     pattern: no fill, and one CHOLMOD analysis of S_c is as cheap as that of S_vv.
// Single candidates are taken in order of increasing degree (fewest neighbours first),
// greedily.  For the scalar P1+/P0 (seed eqs. 10–11 with H^h = P0) the single rule alone
// picks exactly the bubbles: a bubble λ1λ2λ3 lives in one cell, is never constrained,
// couples only with the vertices of its cell (A_vb = 0 already, M_vb = B_Kv B_Kb / |K|
// through C = diag|K|), and those vertices are coupled to each other.  In elasticity a
// cell's bubble has one unknown per component, coupled to each other by A
// ((λ + μ) ∫ ∂_x b ∂_y b ≠ 0 on a general cell) and each to one component of the
// vertices: no single one of them has a clique of neighbours, the cell's block does
// (the vertex unknowns of a cell are all coupled).  At n = 160 the membrane's step
// system shrinks from 76 481 to 25 281 unknowns (docs/performance.md), the unit cube's
// at n = 32 from 697 635 to 107 811.
//
// reduce() and expand() are gathers, one entry of the result per kept unknown or
// condensed block, shared among the threads (linalg/parallel.hpp): r_c from S_bv's
// columns, X_b from S's columns b.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class StaticCondensation {
 public:
  // S symmetric (both triangles stored, compressed), bounds of the same size; blocks:
  // groups of unknowns to condense together where the rules above allow (each unknown
  // in one block at most; at most kMaxBlock unknowns a block).  InputError otherwise.
  // single_unknowns = false: the blocks only — for a subdomain's share of S
  // (mesh/sub_mesh.hpp), whose pattern is not the whole S's: a vertex whose neighbours
  // are a clique in the share may not be in the sum, while a cell's bubble is in both.
  StaticCondensation(const SparseMatrix& S, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                     const std::vector<std::vector<int>>& blocks = {}, bool single_unknowns = true);
  static constexpr int kMaxBlock = 3;

  int n() const { return static_cast<int>(kept_of_.size()); }        // all unknowns
  int n_kept() const { return static_cast<int>(kept_.size()); }
  int n_condensed() const { return static_cast<int>(condensed_.size()); }
  bool condenses(int i) const { return kept_of_[i] < 0; }
  // The kept unknowns, increasing: unknown kept_unknowns()[k] is the condensed QP's k.
  const std::vector<int>& kept_unknowns() const { return kept_; }

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
  // y_g = S_gg⁻¹ z_g on block g's entries of y (its unknowns condensed_[first_[g] ...]).
  void solve_block(int g, double* y) const;

  SparseMatrix S_;                 // the full S (its columns b are read by expand)
  SparseMatrix S_bv_;              // S_bv: column j lists the condensed neighbours of kept j (reduce)
  SparseMatrix S_c_;
  std::vector<int> kept_, condensed_;  // unknown indices; condensed_ block by block
  std::vector<int> kept_of_;       // unknown → index among kept, or −1 when condensed
  std::vector<int> first_;         // block g is condensed_[first_[g] .. first_[g + 1])
  // S_gg⁻¹ of each block, m × m entries from inverse_at_[g] (m = 1: S_bb itself, which
  // y_b = z_b / S_bb divides by)
  std::vector<double> inverse_;
  std::vector<int> inverse_at_;
};

}  // namespace cdyn
