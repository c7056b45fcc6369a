// projected_newton.hpp — Bertsekas' projected Newton method for the step QP
//     min f(X) = ½ XᵀSX − rᵀX   subject to  lower ≤ X ≤ upper,
// the fallback of the primal-dual active set method (pdas.hpp) once its active set has
// come back (a cycle).
//
// D. P. Bertsekas, "Projected Newton methods for optimization problems with simple
// constraints", SIAM J. Control Optim. 20 (1982) 221–246.  From a feasible X, with
// λ = ∇f(X) = S X − r:
//   - the ε-active set  A = {i : X_i ≤ lower_i + ε, λ_i > 0} ∪ {i : X_i ≥ upper_i − ε, λ_i < 0}
//     (and the fixed unknowns), ε = min(ε̄, ‖F(X)‖∞) with F the natural residual of
//     qp/kkt.hpp, so that A is the active set of the solution once X is close to it;
//   - the direction p: a Newton step on the free unknowns, S_II p_I = −λ_I, a diagonally
//     scaled gradient step on A, p_A = −D_A⁻¹ λ_A (D = diag S);
//   - Armijo's rule along the projection arc X(t) = P(X + t p), t = 1, ½, ¼, …:
//     f(X) − f(X(t)) ≥ σ (Σ_{i∈A} λ_i (X_i − X_i(t)) − t Σ_{i∉A} λ_i p_i),  σ = 1e-4.
// It is a descent method for any symmetric positive definite S (where plain PDAS may
// cycle: it converges monotonically only for M-matrices, Hintermüller, Ito & Kunisch
// 2002, Thm 3.3), and once A is the solution's active set the full Newton step is
// accepted and solves the QP: it still ends finitely.
#pragma once

#include <string>

#include "cdyn/qp/pdas/reduced_system.hpp"

namespace cdyn {

struct ProjectedNewtonResult {
  Eigen::VectorXd X;    // the last accepted iterate
  int iterations = 0;   // the caller's count on entry plus the iterations made here
  std::string failure;  // empty when kkt_residual(X) ≤ tol, else why it stopped
};

// From the projection of X on the box, until kkt_residual ≤ options.tol, a stalled line
// search, or options.max_iterations iterations in all (`iterations` made before).  The
// Newton directions are solved by `system` (its held set becomes the ε-active set), to
// tolerance(X, tight).  Each iteration is counted in counters.damped_iterations.
ProjectedNewtonResult projected_newton(const BoundQP& qp, const QuadraticForm& form, ReducedSystem& system,
                                       Eigen::VectorXd X, int iterations, const QPOptions& options,
                                       const SolveTolerance& tolerance, PDASCounters& counters);

}  // namespace cdyn
