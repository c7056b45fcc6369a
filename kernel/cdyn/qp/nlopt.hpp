// nlopt.hpp — the step QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp/bound_qp.hpp) by a
// bound-constrained gradient method of NLopt: LD_LBFGS (Lukšan's limited-memory BFGS,
// Nocedal, Math. Comp. 35 (1980) 773–782, with bounds) or LD_CCSAQ (Svanberg, SIAM J.
// Optim. 12 (2002) 555–573), chosen by QPOptions::nlopt_algorithm.
//
// Matrix-free: NLopt sees f(X) = ½ XᵀSX − rᵀX and ∇f = S X − r only, S applied as a
// product (in saddle form A X + c Bᵀ C⁻¹ B X with C factorized once).  Meant for small
// problems (a few thousand unknowns) and as an independent check of the other solvers:
// its iteration count grows like √cond(S) at best.
//
// Stopping: each evaluation computes the common KKT residual; NLopt is stopped as soon
// as it is ≤ tol.  If NLopt stops before (its own tolerances, round-off), the result is
// polished, at most QPOptions::nlopt_polish_rounds times: the active set is identified
// by the PDAS rule of qp/pdas/pdas.hpp from (X, λ), the active unknowns are put on their
// bounds and S_II X_I = r_I − S_IA X_A is solved by Jacobi-preconditioned conjugate
// gradients (matrix-free too).  Still above tol after that: NumericalError.
// iterations: products with S (NLopt evaluations + CG iterations); default
// max_iterations 20000 evaluations.
#pragma once

#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class NLoptSolver : public StepSolver {
 public:
  explicit NLoptSolver(const QPOptions& options = {});
  std::string name() const override { return "nlopt"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) override;

 private:
  QPOptions options_;
  CheckedMatrices checked_;  // input checks (and the PD check of S) once per distinct S
  QuadraticForm form_;
};

}  // namespace cdyn
