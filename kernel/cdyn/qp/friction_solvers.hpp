// friction_solvers.hpp — solving the frictional step problem (FQP) of qp/friction_qp.hpp.
//
// Two methods, one residual (friction_residual), one tolerance:
//
//  - solve_friction_ssn: a semismooth Newton / primal-dual active set method on the
//    proximal form of the friction law (Hüeber, Stadler, Wohlmuth, SIAM J. Sci. Comput.
//    30 (2008)).  Each contact node's tangential unknown is either *sticking*, held at
//    X̂_T (a bound lower = upper = X̂_T of the bound QP), or *slipping* in the direction
//    σ, free with the constant force −s σ moved into r.  Given these sets the step is an
//    ordinary bound QP (qp/bound_qp.hpp: the normal Signorini bounds are left to the
//    inner step solver, pdas, ipopt or nlopt, which is itself a semismooth Newton method
//    for them), and the sets are updated from y = d − λ_T/D:  stick where |y| ≤ s/D,
//    slip with σ = y/|y| elsewhere — Newton's step on d = shrink(d − λ_T/D, s/D).  So
//    the outer loop around an existing bound-QP solver *is* a semismooth Newton method
//    for the tangential part.  Coulomb: the sets are iterated with s fixed until they
//    repeat, then s = μ λ_N of that Tresca solution (a fixed point on the threshold;
//    updating s at every set update cycled, docs/friction.md).  A cold start sticks
//    everywhere (the bonded step).  Newton's method for a nonsmooth equation converges
//    only locally: when a set comes back for the same s, the Tresca problem of s is
//    solved by solve_friction_pgs below (explicit S) and its sets start the next Newton
//    step.  In space (two tangential unknowns) σ is a unit vector, not one of finitely
//    many: the Tresca problem counts as solved once its residual is below tol, an
//    iteration that does not reduce it tenfold counts as a cycle, and the fallback
//    solves the whole Coulomb problem.  It stops when friction_residual ≤ tol.
//
//  - solve_friction_pgs: projected Gauss–Seidel on the unknowns (the nodal form of the
//    Moreau–Jean NSCD method, M. Jean, CMAME 177 (1999)): each unknown in turn set to
//    the exact minimizer of (FQP) along it — the projection on [lower, upper] for a
//    bounded one, X̂_T + shrink(z − X̂_T, s/S_ii) (a soft threshold) for a tangential one,
//    z the unconstrained minimizer.  For Tresca this is coordinate descent on a strongly
//    convex function with a separable nonsmooth part, which converges (Tseng 2001);
//    Coulomb takes s = μ λ_N from the current normal reaction before each tangential
//    update.  In space a node's two tangential unknowns are one block, moved by the
//    proximal gradient step shrink(d − g/L, s/L), L = λ_max of the block of S (a step
//    that never increases (FQP)).  Explicit S only.
//
// A method that does not reach tol throws NumericalError (or, with throw_on_failure =
// false, returns converged = false): a step is never accepted silently.
#pragma once

#include "cdyn/qp/friction_qp.hpp"
#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

struct FrictionOptions {
  double tol = 1e-10;           // on friction_residual
  int max_iterations = 0;       // 0: ssn 50 outer iterations, pgs 100000 sweeps
  int pgs_check_every = 10;     // pgs: sweeps between two evaluations of the residual
  bool throw_on_failure = true;
};

// qp's r and bounds are changed during the call (the sets) and restored on return.
// `inner` solves the bound QPs (its own tol should be at most options.tol).  warm_start:
// the previous step's result (its sets, thresholds and X).
FrictionResult solve_friction_ssn(BoundQP& qp, const FrictionConditions& f, StepSolver& inner,
                                  const FrictionOptions& options, const FrictionResult* warm_start = nullptr);

FrictionResult solve_friction_pgs(const BoundQP& qp, const FrictionConditions& f, const FrictionOptions& options,
                                  const FrictionResult* warm_start = nullptr);

}  // namespace cdyn
