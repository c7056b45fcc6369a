// distributed_pdas.cpp — the primal-dual active set method (Hintermüller, Ito and
// Kunisch, SIAM J. Optim. 13 (2002)) on the distributed step QP, each reduced system by
// preconditioned CG (kernel/plugins/petsc/distributed_qp.hpp).
//
// With D = diag(S) and λ = S X − r, an unknown is held at its lower bound when
// λ_i > D_i (X_i − lower_i) and at its upper bound when λ_i < D_i (X_i − upper_i), the
// rule of the serial pdas (qp/pdas/pdas.hpp).  The held set A fixed, the iterate solves
//     X_A = bound_A,     S_II X_I = r_I − S_IA X_A,
// written as one system in S's pattern: the rows and columns of A replaced by the
// identity's (MatZeroRowsColumns moves S_IA X_A to the right-hand side).  The method
// stops when A no longer changes, which for an S with positive diagonal and the
// M-matrix-like step matrices converges in a few iterations from a warm start.
//
// CG's stopping test.  The kernel's KKT residual measures the free unknowns by
// max_i |λ_i| / D_i over max(‖X‖∞, ‖D⁻¹r‖∞) (qp/kkt.hpp); CG's unpreconditioned
// residual ‖b − S̃X‖₂ ≥ max_i |λ_i| bounds it by ‖·‖₂ / (min_i D_i ‖D⁻¹r‖∞), so CG
// runs to a hundredth of tol in that measure and the KKT test on rank 0 passes.
#include <algorithm>
#include <cmath>
#include <vector>

#include "cdyn/base/error.hpp"
#include "distributed_qp.hpp"

namespace cdyn::petsc {

namespace {

// Which bound holds each local unknown: −1 lower, +1 upper, 0 free.
std::vector<signed char> held_set(DistributedQP& q, Vec D) {
  const PetscScalar *x, *lam, *l, *u, *d;
  VecGetArrayRead(q.X, &x), VecGetArrayRead(q.reaction, &lam), VecGetArrayRead(q.lower, &l),
      VecGetArrayRead(q.upper, &u), VecGetArrayRead(D, &d);
  const PetscInt m = q.last - q.first;
  std::vector<signed char> held(m, 0);
  for (PetscInt i = 0; i < m; ++i) {
    if (std::isfinite(l[i]) && lam[i] > d[i] * (x[i] - l[i])) held[i] = -1;
    else if (std::isfinite(u[i]) && lam[i] < d[i] * (x[i] - u[i])) held[i] = 1;
  }
  VecRestoreArrayRead(q.X, &x), VecRestoreArrayRead(q.reaction, &lam), VecRestoreArrayRead(q.lower, &l),
      VecRestoreArrayRead(q.upper, &u), VecRestoreArrayRead(D, &d);
  return held;
}

// max over the ranks of a local number
double global_max(double local) {
  double out = 0.0;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return out;
}

// ‖D⁻¹r‖∞ (at least the largest finite bound, so that a QP with r = 0 still has a scale).
double solution_scale(DistributedQP& q, Vec D) {
  const PetscScalar *r, *d, *l, *u;
  VecGetArrayRead(q.r, &r), VecGetArrayRead(D, &d), VecGetArrayRead(q.lower, &l), VecGetArrayRead(q.upper, &u);
  double s = 0.0;
  for (PetscInt i = 0; i < q.last - q.first; ++i) {
    s = std::max(s, std::abs(r[i] / d[i]));
    if (std::isfinite(l[i])) s = std::max(s, std::abs(l[i]));
    if (std::isfinite(u[i])) s = std::max(s, std::abs(u[i]));
  }
  VecRestoreArrayRead(q.r, &r), VecRestoreArrayRead(D, &d), VecRestoreArrayRead(q.lower, &l),
      VecRestoreArrayRead(q.upper, &u);
  s = global_max(s);
  return s > 0 ? s : 1.0;
}

// λ = S X − r
void update_reaction(DistributedQP& q) {
  check(MatMult(q.S, q.X, q.reaction), "MatMult");
  check(VecAXPY(q.reaction, -1.0, q.r), "VecAXPY");
}

// CG on an indefinite S can converge (to a saddle point) without noticing.  Its Lanczos
// coefficients give Ritz values of the preconditioned operator P⁻¹S̃, which for an SPD
// preconditioner P has the inertia of S̃ (Sylvester's law): a negative one proves S̃,
// hence S, indefinite.  (Free of cost: a tridiagonal eigenproblem of CG's iterations.)
bool positive_ritz_values(KSP ksp) {
  PetscInt its = 0, found = 0;
  check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
  if (its == 0) return true;
  std::vector<PetscReal> re(its + 1), im(its + 1);
  check(KSPComputeEigenvalues(ksp, its + 1, re.data(), im.data(), &found), "KSPComputeEigenvalues");
  for (PetscInt k = 0; k < found; ++k)
    if (re[k] < 0) return false;
  return true;
}

}  // namespace

int distributed_pdas(DistributedQP& q, const SolveSettings& settings, bool warm) {
  const int max_iterations = settings.max_iterations > 0 ? settings.max_iterations : 100;
  Vec D = nullptr, b = nullptr;
  Mat S_held = nullptr;
  KSP ksp = nullptr;
  check(VecDuplicate(q.r, &D), "VecDuplicate");
  check(VecDuplicate(q.r, &b), "VecDuplicate");
  check(MatGetDiagonal(q.S, D), "MatGetDiagonal");
  PetscReal min_d = 0.0;
  check(VecMin(D, nullptr, &min_d), "VecMin");
  if (!(min_d > 0)) throw NumericalError("petsc pdas: S has a diagonal entry ≤ 0 (not positive definite)");
  const double atol = 1e-2 * settings.tol * min_d * solution_scale(q, D);
  project_on_box(q);
  if (!warm) update_reaction(q);

  check(MatDuplicate(q.S, MAT_COPY_VALUES, &S_held), "MatDuplicate");
  check(KSPCreate(PETSC_COMM_WORLD, &ksp), "KSPCreate");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  configure_krylov(ksp, settings.pc, /*fixed_size=*/true);
  check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  check(KSPSetTolerances(ksp, 1e-300, atol, PETSC_DEFAULT, 10000), "KSPSetTolerances");
  check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  check(KSPSetComputeEigenvalues(ksp, PETSC_TRUE), "KSPSetComputeEigenvalues");

  std::vector<signed char> held_before;
  std::vector<PetscInt> rows;
  int iterations = 0;
  std::string failure;
  for (; iterations < max_iterations; ++iterations) {
    const std::vector<signed char> held = held_set(q, D);
    double changed = held_before.empty() ? 1.0 : 0.0;
    for (std::size_t i = 0; i < held_before.size(); ++i) changed += held[i] != held_before[i];
    if (global_max(changed) == 0.0) break;  // the held set is the last one: X solves the QP
    held_before = held;
    // X_A = bound_A, then the system in S's pattern with A's rows and columns the identity's
    rows.clear();
    {
      PetscScalar* x = nullptr;
      const PetscScalar *l, *u;
      VecGetArray(q.X, &x), VecGetArrayRead(q.lower, &l), VecGetArrayRead(q.upper, &u);
      for (std::size_t i = 0; i < held.size(); ++i)
        if (held[i] != 0) {
          rows.push_back(q.first + static_cast<PetscInt>(i));
          x[i] = held[i] < 0 ? l[i] : u[i];
        }
      VecRestoreArray(q.X, &x), VecRestoreArrayRead(q.lower, &l), VecRestoreArrayRead(q.upper, &u);
    }
    double free_count = static_cast<double>(held.size() - rows.size());
    MPI_Allreduce(MPI_IN_PLACE, &free_count, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    if (free_count == 0) {  // every unknown at a bound: X is the bounds, nothing to solve
      update_reaction(q);
      continue;
    }
    check(MatCopy(q.S, S_held, SAME_NONZERO_PATTERN), "MatCopy");
    check(VecCopy(q.r, b), "VecCopy");
    check(MatZeroRowsColumns(S_held, static_cast<PetscInt>(rows.size()), rows.data(), 1.0, q.X, b),
          "MatZeroRowsColumns");
    check(KSPSetOperators(ksp, S_held, S_held), "KSPSetOperators");
    check(KSPSolve(ksp, b, q.X), "KSPSolve");
    KSPConvergedReason reason;
    check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
    if (reason < 0) {
      failure = std::string("CG on the reduced system: ") + KSPConvergedReasons[reason] +
                (reason == KSP_DIVERGED_INDEFINITE_MAT || reason == KSP_DIVERGED_INDEFINITE_PC
                     ? " (S is not positive definite)"
                     : "");
      break;
    }
    if (!positive_ritz_values(ksp)) {
      failure = "S is not positive definite (CG's Lanczos estimates show a negative eigenvalue)";
      break;
    }
    update_reaction(q);
  }
  KSPDestroy(&ksp);
  MatDestroy(&S_held);
  VecDestroy(&D);
  VecDestroy(&b);
  // (the same on every rank: the reason and the held-set test are global)
  if (!failure.empty()) throw NumericalError("petsc pdas: " + failure);
  return iterations;
}

}  // namespace cdyn::petsc
