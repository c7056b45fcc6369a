// pdas.hpp — the primal-dual active set method (a semismooth Newton method) for the
// step QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp/bound_qp.hpp).  The default step solver.
//
// Hintermüller, Ito & Kunisch, "The primal-dual active set strategy as a semismooth
// Newton method", SIAM J. Optim. 13 (2002) 865–888.  With λ = S X − r and D = diag(S),
// the KKT conditions are the (semismooth) equation
//     λ = max(0, λ + D(lower − X)) + min(0, λ + D(upper − X)),
// and Newton's method on it is the iteration
//     A_l = {i : λ_i + D_i(lower_i − X_i) > 0},   A_u = {i : λ_i + D_i(upper_i − X_i) < 0},
//     X = lower on A_l,  X = upper on A_u,  (S X − r)_i = 0 on the other unknowns I,
//     λ = S X − r,
// one sparse SPD solve with S_II per iteration.  It stops when the active set repeats
// (X is then the exact solution) or kkt_residual ≤ tol.  Started from the previous
// step's active set, it usually ends after one or two solves.
//
// Linear algebra.  The system on I is solved as S̃ X = b̃, with S̃ = S whose rows and
// columns in A = A_l ∪ A_u are replaced by the identity's, kept in S's pattern (explicit
// zeros), so that
//   - explicit S: one CHOLMOD analysis serves every active set and every call; the
//     numeric factor is kept across calls (a time loop with an unchanged S and active
//     set pays one forward/back solve per step); a change of at most
//     QPOptions::pdas_update_limit unknowns (default max(300, n/100)) is applied to the
//     factor by cholmod_rowdel / cholmod_rowadd instead of refactorizing;
//     before any of that, a system whose active set differs from the factorized one
//     is solved by CG on S̃, preconditioned by multicolour symmetric Gauss–Seidel
//     (linalg/masked_cg.hpp, QPOptions::pdas_cg_iterations) when that costs fewer flops than
//     the row updates: for a well-conditioned S (the condensed P1+/P0 step matrix) a CG
//     iteration costs a seventh of a forward/back solve, against a factorization (≈ 15 solves) or
//     hundreds of row updates (≈ 0.1 solve each) when the contact zone jumps; the
//     factor follows once the set has settled.  CG stops at a residual in the units of
//     kkt_residual: loosely (1e-4 of the solution's scale) for an iterate that only
//     decides the next active set, and at tol/2 to confirm the set that repeats (the
//     same CG iteration resumed; inexact semismooth Newton: the final X meets tol like a
//     direct solve's); between iterates λ on the free rows is CG's residual;
//   - saddle form: the same elimination in K = [[A, c Bᵀ], [B, −C]] (X rows only), LU
//     by UMFPACK, symbolic analysis kept while K's pattern is unchanged; no updates.
// A new explicit S is factorized once whole first: that checks it is positive definite
// (NumericalError otherwise) and gives the unconstrained solution of a cold start.
//
// Cycling guard.  For an S that is not an M-matrix, plain PDAS may cycle.  When an
// active set comes back, the solver switches to Bertsekas' projected Newton method
// (SIAM J. Control Optim. 20 (1982) 221–246): ε-active set, Newton step on the free
// unknowns, scaled gradient step on the active ones, Armijo search along the projection
// arc — a descent method on ½XᵀSX − rᵀX that converges for any SPD S and still
// terminates finitely on a QP.  Failure (max_iterations, default 100, or a stalled line
// search) throws NumericalError with the residual and the iteration count.
#pragma once

#include <memory>

#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class PDASSolver : public StepSolver {
 public:
  explicit PDASSolver(const QPOptions& options = {});
  ~PDASSolver() override;
  std::string name() const override { return "pdas"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) override;

  // Work done since construction (for tests and benchmarks).
  struct Counters {
    int analyses = 0;        // symbolic analyses (CHOLMOD or UMFPACK)
    int factorizations = 0;  // numeric factorizations
    int row_updates = 0;     // cholmod_rowadd / cholmod_rowdel calls
    int solves = 0;          // forward/back solves
    int damped_iterations = 0;  // projected Newton iterations after a detected cycle
    int cg_solves = 0;       // systems solved by preconditioned CG instead of the factor
    int cg_iterations = 0;   // their CG iterations (one product with S each)
    // Wall time in each kind of linear algebra (explicit S; for profiling, bench/):
    double factorization_s = 0, row_update_s = 0, solve_s = 0, cg_s = 0;
  };
  const Counters& counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdyn
