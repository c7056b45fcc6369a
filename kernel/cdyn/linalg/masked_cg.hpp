// linalg/masked_cg.hpp — preconditioned conjugate gradients on S̃ y = b, where S̃ is the
// symmetric positive definite S with the rows and columns of a held set A replaced by the
// identity's (the reduced system of an active-set step, qp/pdas/reduced_system.hpp):
//     y_i = b_i  (i ∈ A),        Σ_{j ∉ A} S_ij y_j = b_i  (i ∉ A),
// where b_I already carries −S_IA y_A.
// On A y is set to b and every vector of the iteration vanishes, so this is CG on S_II
// alone (I = the complement of A), run in S's storage without forming S_II.
//
// Preconditioner: symmetric Gauss–Seidel in a multicolour ordering, applied by
// Eisenstat's trick (linalg/symmetric_gauss_seidel.hpp): an iteration is one backward and one
// forward sweep, which together read S once, as the product of a Jacobi-preconditioned
// iteration does, and CG needs 2–2.5 times fewer of them than with Jacobi on the
// condensed P1+/P0 step matrix.
//
// Stopping test: the Jacobi-scaled residual max_{i ∉ A} |b − S̃y|_i / S_ii ≤ tol.
// In PDAS this quantity is exactly the natural residual that kkt_residual measures on
// the free unknowns (λ_i / D_i, qp/kkt.hpp), so `tol` is set in the units of the QP's own
// convergence test rather than as a relative 2-norm that has to be guessed tight enough.
// CG carries the preconditioned residual r̂ = L̂⁻¹ D^{-1/2} r; the test is made on
// max |r̂_i| / S_ii^{1/2} first (within a factor 1 + ‖L̂ − I‖∞ of the true quantity) and,
// when that passes, on r itself, D^{1/2} L̂ r̂ (one sweep's worth of reading).
//
// Threads: the product, the sweeps and the vector updates are shared among the threads,
// and the reductions are summed by blocks of a fixed length, so that the iterates do not
// depend on the thread count, bit for bit (linalg/parallel.hpp).
//
// On the condensed P1+/P0 membrane (n = 160, 25k unknowns, the contact window of
// docs/performance.md (a)) a solve takes 5 iterations on average, 0.25 ms each with its
// share of the solve's set-up (the first residual is one more pass over S's triangles):
// a seventh of a forward/back solve with the Cholesky factor where that was measured
// (1.7 ms), a fifth of one (1.1–1.3 ms) on a later machine and with the kernel's own
// sweeps (linalg/supernodal_solve.hpp).  An iteration reads S's triangles and six vectors, more
// than a 2 MB L2 holds: its time is the bytes it reads (docs/performance.md, "Contact in
// every regime", eighteenth session).
#pragma once

#include <vector>

#include "cdyn/base/sparse.hpp"
#include "cdyn/linalg/symmetric_gauss_seidel.hpp"

namespace cdyn {

struct MaskedCGResult {
  int iterations = 0;
  bool converged = false;
  double scaled_residual = 0.0;  // max_{i ∉ A} |b − S̃y|_i / S_ii at return
};

// The iteration for one S: its preconditioner (built once, O(nnz)) and work vectors
// (kept between solves: a PDAS step calls it several times), and the residual it ends with.
class MaskedCG {
 public:
  // S: symmetric, full storage, compressed, positive diagonal.  Its entries are copied
  // into the preconditioner's scaled triangles, which serve every pass over S (the first
  // residual's too): new values of S need a new MaskedCG.
  explicit MaskedCG(const SparseMatrix& S);

  // Solves S̃ y = b from the first guess y (resized to zero if it has the wrong size);
  // held[i] ≠ 0 marks A.  resume: the same held set, b and y as the last solve, which
  // converged, now to a smaller tol (PDAS's confirmation of a repeating active set):
  // the interrupted iteration goes on (no new residual, no restart of the Krylov space).
  MaskedCGResult solve(const std::vector<char>& held, const Eigen::VectorXd& b, Eigen::VectorXd& y, double tol,
                       int max_iterations, bool resume = false);

  // b − S̃y at the last return, as CG updates it (0 on A).  It differs from the residual
  // recomputed from y by round-off, about ε ‖S‖ ‖y‖ per iteration.  In PDAS it is −λ on
  // the free unknowns (qp/pdas/explicit_reduced_system.cpp), which then costs no product with S.
  const Eigen::VectorXd& residual() const { return r_; }

 private:
  SymmetricGaussSeidel sgs_;
  Eigen::VectorXd D_, inverse_sqrt_D_;  // diag(S), diag(S)^{-1/2}
  Eigen::VectorXd r_, r_hat_, p_, t_, w_, q_;
  std::vector<double> block_rr_;  // the blocks' shares of r̂ᵀr̂ (linalg/parallel.hpp)
  // The set-up of a fresh solve, over all rows or over the free ones; each returns the
  // scaled residual of the first guess.
  double set_up_on_all_rows(const std::vector<char>& held, const Eigen::VectorXd& b, Eigen::VectorXd& y, double tol);
  double set_up_on_free_rows(const std::vector<char>& held, const Eigen::VectorXd& b, Eigen::VectorXd& y, double tol);

  // most rows held: the iterations on the free rows alone (free_, in increasing order)
  bool compact_ = false;
  std::vector<int> free_;
  SymmetricGaussSeidel::FreeRows free_rows_;
  // zero_outside_: the work vectors vanish outside the rows written_ (by the last solve
  // on free rows), so that the next one clears those rows alone
  bool zero_outside_ = false;
  std::vector<int> written_;
  // the state an iteration that converged stops in, for resume
  bool resumable_ = false;
  double rr_ = 0.0, rr_next_ = 0.0, last_scaled_ = 0.0;  // r̂ᵀr̂ for p_, r̂ᵀr̂ now, the test's value
};

// One solve with a fresh preconditioner.
inline MaskedCGResult masked_cg(const SparseMatrix& S, const std::vector<char>& held, const Eigen::VectorXd& b,
                                Eigen::VectorXd& y, double tol, int max_iterations) {
  return MaskedCG(S).solve(held, b, y, tol, max_iterations);
}

}  // namespace cdyn
