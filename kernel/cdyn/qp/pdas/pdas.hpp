// pdas.hpp — the primal-dual active set method (a semismooth Newton method) for the
// step QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp/bound_qp.hpp).  The default step
// solver.
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
// (X is then the exact solution up to the linear solve) or kkt_residual ≤ tol.  Started
// from the previous step's active set, it usually ends after one or two solves.
//
// The files of this folder, one concept each:
//   pdas.{hpp,cpp}                 the iteration above (this class);
//   reduced_system.hpp             the interface "solve S_II X_I = r_I − S_IA X_A for this
//                                  active set", and the tolerance of an inexact solve;
//   explicit_reduced_system.hpp    its implementation for an explicit S: CHOLMOD factor
//                                  kept across calls, row updates, masked CG;
//   saddle_reduced_system.hpp      its implementation for the saddle form: UMFPACK;
//   projected_newton.hpp           the fallback after a cycling active set (Bertsekas 1982);
//   reference_pdas.hpp             the same iteration in textbook form (a test oracle).
//
// Inexact iterates.  When a system is solved by CG (explicit_reduced_system.hpp), an
// iterate is solved loosely (it only decides the next active set) and a repeating set is
// confirmed on a tight solve before it is believed (SolveTolerance); the final X meets
// tol as a direct solve's does.  A result whose set repeated but whose residual is above
// tol gets two steps of iterative refinement, then one fresh factorization.
//
// Cycling guard.  For an S that is not an M-matrix, plain PDAS may cycle.  When an
// active set comes back, the solver switches to projected Newton (projected_newton.hpp),
// a descent method that converges for any SPD S.  Failure (max_iterations, default 100,
// or a stalled line search) throws NumericalError with the residual and the iteration
// count.
#pragma once

#include <memory>

#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/pdas/reduced_system.hpp"
#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class PDASSolver : public StepSolver {
 public:
  explicit PDASSolver(const QPOptions& options = {});
  ~PDASSolver() override;
  std::string name() const override { return "pdas"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) override;
  void clear() override;
  void next_in_same_step(bool to_round_off) override;

  // Work done since construction or the last clear() (for tests and benchmarks; cg_pays
  // steers by the CG counts): analyses, factorizations,
  // row updates, solves, projected Newton iterations, CG solves and iterations, and the
  // seconds spent in each kind of linear algebra.
  using Counters = PDASCounters;
  const Counters& counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdyn
