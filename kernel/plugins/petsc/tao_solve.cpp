// tao_solve.cpp — the step QP by PETSc's TAO bound-constrained solvers: TRON (trust-region
// Newton, Lin and Moré 1999), GPCG (gradient projection with CG, Moré and Toraldo 1991),
// BQNLS (bounded quasi-Newton line search) and BNCG (bounded nonlinear CG).
//
// TAO minimizes f(X) = ½ XᵀSX − rᵀX with gradient S X − r and Hessian S between the
// bounds, and stops on its own gradient test; the result is then brought to the
// kernel's tol by active-set iterations started from TAO's X (the crossover the serial
// Ipopt solver makes, qp/ipopt.hpp), so that every solver returns the same accuracy.
#include <petsctao.h>

#include "cdyn/base/error.hpp"
#include "distributed_qp.hpp"

namespace cdyn::petsc {

namespace {

PetscErrorCode objective_and_gradient(Tao, Vec X, PetscReal* f, Vec g, void* context) {
  auto* q = static_cast<DistributedQP*>(context);
  PetscScalar rx = 0.0, xg = 0.0;
  PetscCall(MatMult(q->S, X, g));   // g = S X
  PetscCall(VecDot(X, g, &xg));     // Xᵀ S X
  PetscCall(VecDot(X, q->r, &rx));  // rᵀ X
  PetscCall(VecAXPY(g, -1.0, q->r));
  *f = 0.5 * xg - rx;
  return 0;
}

PetscErrorCode constant_hessian(Tao, Vec, Mat, Mat, void*) { return 0; }  // S, set once

TaoType tao_type(Algorithm a) {
  switch (a) {
    case Algorithm::tao_tron: return TAOTRON;
    case Algorithm::tao_gpcg: return TAOGPCG;
    case Algorithm::tao_bqnls: return TAOBQNLS;
    default: return TAOBNCG;
  }
}

}  // namespace

int tao_solve(DistributedQP& q, const SolveSettings& settings) {
  PetscErrorCode code = 0;
  PetscInt iterations = 0;
  {  // (TAO and the bounds freed before the crossover)
    Owned<Tao, TaoDestroy> tao;
    Owned<Vec, VecDestroy> l, u;
    petsc_bounds(q, l.out(), u.out());
    check(TaoCreate(PETSC_COMM_WORLD, tao.out()), "TaoCreate");
    check(TaoSetType(tao, tao_type(settings.algorithm)), "TaoSetType");
    check(TaoSetSolution(tao, q.X), "TaoSetSolution");
    check(TaoSetObjectiveAndGradient(tao, nullptr, objective_and_gradient, &q), "TaoSetObjectiveAndGradient");
    check(TaoSetHessian(tao, q.S, q.S, constant_hessian, &q), "TaoSetHessian");
    check(TaoSetVariableBounds(tao, l, u), "TaoSetVariableBounds");
    // TAO's projected-gradient test relative to the start's, to 1e-8: enough to find the
    // active set, which the crossover takes to tol in a solve or two.  Pushed to tol
    // itself, GPCG and BQNLS run into their iteration limit (measured: 10⁴ iterations,
    // 11 s and 2 s, on 900 unknowns whose pdas takes 0.02 s).
    check(TaoSetTolerances(tao, 0.0, 1e-8, 0.0), "TaoSetTolerances");
    check(TaoSetMaximumIterations(tao, settings.max_iterations > 0 ? settings.max_iterations : 1000),
          "TaoSetMaximumIterations");
    KSP ksp = nullptr;
    check(TaoGetKSP(tao, &ksp), "TaoGetKSP");
    if (ksp) configure_krylov(ksp, settings.pc, /*fixed_size=*/false);  // TAO's own Krylov method
    check(TaoSetFromOptions(tao), "TaoSetFromOptions");
    code = TaoSolve(tao);
    TaoGetIterationNumber(tao, &iterations);
  }
  check(code, "TaoSolve");
  // Whatever TAO's own verdict, the crossover from its X decides (and rank 0's KKT test).
  check(MatMult(q.S, q.X, q.reaction), "MatMult");
  check(VecAXPY(q.reaction, -1.0, q.r), "VecAXPY");
  return static_cast<int>(iterations) + distributed_pdas(q, settings, /*warm=*/true);
}

}  // namespace cdyn::petsc
