// snesvi_solve.cpp — the step QP as PETSc's variational inequality: find X in the box
// with F(X) = S X − r ≥ 0 where X is at its lower bound, ≤ 0 at its upper, 0 between —
// the KKT conditions of qp/bound_qp.hpp — by SNESVI's reduced-space active set Newton
// method (SNESVINEWTONRSLS, Benson and Munson 2006), CG on the inactive block.
//
// As for TAO (tao_solve.cpp), the result is brought to the kernel's tol by active-set
// iterations from SNESVI's X.
#include <petscsnes.h>

#include "cdyn/base/error.hpp"
#include "distributed_qp.hpp"

namespace cdyn::petsc {

namespace {

PetscErrorCode residual(SNES, Vec X, Vec F, void* context) {
  auto* q = static_cast<DistributedQP*>(context);
  PetscCall(MatMult(q->S, X, F));
  PetscCall(VecAXPY(F, -1.0, q->r));
  return 0;
}

PetscErrorCode constant_jacobian(SNES, Vec, Mat, Mat, void*) { return 0; }  // S, set once

}  // namespace

int snesvi_solve(DistributedQP& q, const SolveSettings& settings) {
  PetscErrorCode code = 0;
  PetscInt iterations = 0;
  {  // (SNES, the bounds and F freed before the crossover)
    Owned<SNES, SNESDestroy> snes;
    Owned<Vec, VecDestroy> l, u, F;
    petsc_bounds(q, l.out(), u.out());
    check(VecDuplicate(q.r, F.out()), "VecDuplicate");
    check(SNESCreate(PETSC_COMM_WORLD, snes.out()), "SNESCreate");
    check(SNESSetType(snes, SNESVINEWTONRSLS), "SNESSetType");
    check(SNESSetFunction(snes, F, residual, &q), "SNESSetFunction");
    check(SNESSetJacobian(snes, q.S, q.S, constant_jacobian, &q), "SNESSetJacobian");
    check(SNESVISetVariableBounds(snes, l, u), "SNESVISetVariableBounds");
    check(SNESSetTolerances(snes, 1e-2 * settings.tol, 1e-14, 0.0,
                            settings.max_iterations > 0 ? settings.max_iterations : 200, 10000),
          "SNESSetTolerances");
    KSP ksp = nullptr;
    check(SNESGetKSP(snes, &ksp), "SNESGetKSP");
    check(KSPSetType(ksp, KSPCG), "KSPSetType");  // the reduced systems are S's principal blocks: SPD
    configure_krylov(ksp, settings.pc, /*fixed_size=*/false);
    check(KSPSetTolerances(ksp, 1e-12, PETSC_DEFAULT, PETSC_DEFAULT, 10000), "KSPSetTolerances");
    check(SNESSetFromOptions(snes), "SNESSetFromOptions");
    code = SNESSolve(snes, nullptr, q.X);
    SNESGetIterationNumber(snes, &iterations);
  }
  check(code, "SNESSolve");
  check(MatMult(q.S, q.X, q.reaction), "MatMult");
  check(VecAXPY(q.reaction, -1.0, q.r), "VecAXPY");
  return static_cast<int>(iterations) + distributed_pdas(q, settings, /*warm=*/true);
}

}  // namespace cdyn::petsc
