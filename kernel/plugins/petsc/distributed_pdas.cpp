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
// runs to a hundredth of tol in that measure and the KKT test on rank 0 passes.  The
// scale is not known before X is: CG starts with max(‖D⁻¹r‖∞, the finite bounds) and,
// when the solution's own scale is smaller, goes on from X to the tolerance it asks.
//
// Saddle form (the pairs whose velocity space is continuous, qp/bound_qp.hpp): the
// unknowns are [X; Z] and the matrix K = [[A, c Bᵀ], [c B, −c C]] (base/sparse.hpp), Z
// unbounded, so the held rows are X's only and the same elimination gives K̃ = K with
// A's rows and columns the identity's.  K̃ is indefinite — CG does not apply — and is
// solved as the serial pdas solves it (UMFPACK's LU, qp/pdas/saddle_reduced_system.hpp):
// by a sparse direct factorization, MUMPS's parallel LDLᵀ (symbolic analysis once, a
// numeric factorization per held set).  Its inertia checks what CG's Ritz values check
// for an explicit S: K̃ has exactly m negative eigenvalues iff S̃ and C are positive
// definite (Sylvester's law on K̃'s block LDLᵀ).  The rule's D is the kernel's scaling
// diag(A) + c Σ_k B_kj² / C_kk (qp/kkt.hpp), sent with K.
#include <algorithm>
#include <cmath>
#include <string>
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

// KSP's dtol that never triggers (see distributed_pdas).
constexpr PetscReal kNoDivergenceTest = 1e300;

// Whether two held sets agree on every rank (collective; a rank whose local sets differ
// in size, e.g. against an empty "none yet", counts as a difference).
bool same_on_every_rank(const std::vector<signed char>& a, const std::vector<signed char>& b) {
  double differs = a.size() == b.size() ? 0.0 : 1.0;
  for (std::size_t i = 0; differs == 0.0 && i < a.size(); ++i) differs += a[i] != b[i];
  return global_max(differs) == 0.0;
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

// The KKT test's own scale, max(‖X‖∞, ‖D⁻¹r‖∞), once X is known.
double kkt_scale(DistributedQP& q, Vec D) {
  const PetscScalar *r, *d, *x;
  VecGetArrayRead(q.r, &r), VecGetArrayRead(D, &d), VecGetArrayRead(q.X, &x);
  double s = 0.0;
  for (PetscInt i = 0; i < q.last - q.first; ++i) s = std::max({s, std::abs(r[i] / d[i]), std::abs(x[i])});
  VecRestoreArrayRead(q.r, &r), VecRestoreArrayRead(D, &d), VecRestoreArrayRead(q.X, &x);
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

// K̃'s factor by MUMPS (LDLᵀ of a symmetric indefinite matrix); ICNTL(13) = 1 keeps the
// root front off ScaLAPACK so that the factor's inertia counts every rank's pivots.  One
// step of iterative refinement (Richardson's iteration on the factor, two applications),
// as the serial pdas makes with UMFPACK: without it the membrane's P2/P1 step differed
// from the serial one by 2e-15 at the first step and its velocity at the impact by 3e-7
// of its largest value; with it, by 7e-11 (measured on the membrane, tol = 1e-12).
void configure_direct(KSP ksp, Mat K) {
  PC pc = nullptr;
  Mat F = nullptr;
  check(KSPSetOptionsPrefix(ksp, "cdyn_"), "KSPSetOptionsPrefix");  // before the factor takes it
  check(KSPSetType(ksp, KSPRICHARDSON), "KSPSetType");
  check(KSPSetNormType(ksp, KSP_NORM_NONE), "KSPSetNormType");
  check(KSPSetTolerances(ksp, 0.0, 0.0, PETSC_DEFAULT, 2), "KSPSetTolerances");
  check(KSPSetOperators(ksp, K, K), "KSPSetOperators");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType");
  check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
  check(MatMumpsSetIcntl(F, 13, 1), "MatMumpsSetIcntl");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
}

// MUMPS's error code and its detail (INFOG(1), INFOG(2): its user's guide, chapter 8).
std::string mumps_status(KSP ksp) {
  PC pc = nullptr;
  Mat F = nullptr;
  PetscInt info1 = 0, info2 = 0;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
  check(MatMumpsGetInfog(F, 1, &info1), "MatMumpsGetInfog");
  check(MatMumpsGetInfog(F, 2, &info2), "MatMumpsGetInfog");
  return "INFOG(1) = " + std::to_string(info1) + ", INFOG(2) = " + std::to_string(info2) +
         (info1 == -10 ? ": numerically singular" : "");
}

// The number of negative pivots of the factorized K̃ (a global count; a zero pivot fails
// the factorization itself).
PetscInt negative_eigenvalues(KSP ksp) {
  PC pc = nullptr;
  Mat F = nullptr;
  PetscInt negative = 0;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
  check(MatGetInertia(F, &negative, nullptr, nullptr), "MatGetInertia");
  return negative;
}

// K̃ X = b̃ in saddle form, X_A already at its bounds.  K̃ is factorized again only when
// the held set differs from the one factorized — a step without a change of contact
// costs forward and back solves, as with the serial pdas's LU (measured on the P1+/P1
// membrane, n = 80: refactorizing at every iteration made the run 5.6 times the serial
// one's time).  b̃ = r − K X_A on the free rows and the Z rows, X_A on the held ones.
// Returns the failure, empty on success.
std::string solve_saddle(DistributedQP& q, const std::vector<signed char>& held, const std::vector<PetscInt>& rows,
                         Vec b, Vec X_held, int saddle_rows) {
  const bool refactor = !q.factor || !same_on_every_rank(held, q.factored_held);  // (q.factor: alike on every rank)
  if (!q.factor) {
    check(MatDuplicate(q.S, MAT_COPY_VALUES, &q.K_held), "MatDuplicate");
    check(KSPCreate(PETSC_COMM_WORLD, &q.factor), "KSPCreate");
    configure_direct(q.factor, q.K_held);
  }
  if (refactor) {
    check(MatCopy(q.S, q.K_held, SAME_NONZERO_PATTERN), "MatCopy");
    check(MatZeroRowsColumns(q.K_held, static_cast<PetscInt>(rows.size()), rows.data(), 1.0, nullptr, nullptr),
          "MatZeroRowsColumns");
    check(KSPSetOperators(q.factor, q.K_held, q.K_held), "KSPSetOperators");
    q.factored_held = held;
  }
  // X_A: X on the held rows, 0 elsewhere
  {
    const PetscScalar* x = nullptr;
    PetscScalar* xa = nullptr;
    VecGetArrayRead(q.X, &x), VecGetArray(X_held, &xa);
    for (std::size_t i = 0; i < held.size(); ++i) xa[i] = held[i] != 0 ? x[i] : 0.0;
    VecRestoreArrayRead(q.X, &x), VecRestoreArray(X_held, &xa);
  }
  check(MatMult(q.S, X_held, b), "MatMult");
  check(VecAYPX(b, -1.0, q.r), "VecAYPX");  // r − K X_A
  {
    const PetscScalar* xa = nullptr;
    PetscScalar* bb = nullptr;
    VecGetArrayRead(X_held, &xa), VecGetArray(b, &bb);
    for (std::size_t i = 0; i < held.size(); ++i)
      if (held[i] != 0) bb[i] = xa[i];
    VecRestoreArrayRead(X_held, &xa), VecRestoreArray(b, &bb);
  }
  check(KSPSolve(q.factor, b, q.X), "KSPSolve");
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(q.factor, &reason), "KSPGetConvergedReason");
  std::string failure;
  if (reason < 0)
    failure = "MUMPS's factorization of the reduced saddle system failed (" + mumps_status(q.factor) + ")";
  else if (refactor && negative_eigenvalues(q.factor) != saddle_rows)
    failure = "S or C is not positive definite (the saddle matrix's inertia: " +
              std::to_string(negative_eigenvalues(q.factor)) + " negative eigenvalues for " +
              std::to_string(saddle_rows) + " rows of C)";
  if (!failure.empty()) q.factored_held.clear();  // factorize again at the next solve
  return failure;
}

}  // namespace

int distributed_pdas(DistributedQP& q, const SolveSettings& settings, bool warm) {
  const int max_iterations = settings.max_iterations > 0 ? settings.max_iterations : 100;
  Owned<Vec, VecDestroy> D, b, X_held;  // (X_held: X_A, in saddle form)
  Owned<Mat, MatDestroy> S_held;
  Owned<KSP, KSPDestroy> ksp;
  check(VecDuplicate(q.r, D.out()), "VecDuplicate");
  check(VecDuplicate(q.r, b.out()), "VecDuplicate");
  const bool saddle = settings.saddle_rows > 0;
  if (saddle) {
    check(VecDuplicate(q.r, X_held.out()), "VecDuplicate");
    check(VecCopy(q.D, D), "VecCopy");
  } else {
    check(MatGetDiagonal(q.S, D), "MatGetDiagonal");
  }
  PetscReal min_d = 0.0;
  check(VecMin(D, nullptr, &min_d), "VecMin");
  if (!(min_d > 0)) throw NumericalError("S has a diagonal entry ≤ 0 (not positive definite)");
  double atol = 1e-2 * settings.tol * min_d * solution_scale(q, D);
  project_on_box(q);
  if (!warm) update_reaction(q);

  if (!saddle) {
    check(MatDuplicate(q.S, MAT_COPY_VALUES, S_held.out()), "MatDuplicate");
    check(KSPCreate(PETSC_COMM_WORLD, ksp.out()), "KSPCreate");
    check(KSPSetType(ksp, KSPCG), "KSPSetType");
    configure_krylov(ksp, settings.pc, /*fixed_size=*/true);
    check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    // No divergence test: PETSc's compares the residual with ‖b‖, and a warm start far
    // from a solution near 0 (b ≈ 0: the reconstruction's QP when the data vanish) is
    // "diverged" at iteration 0 (measured: ‖r₀‖ = 8e-3 against ‖b‖ = 5e-16).  CG's
    // breakdowns and an indefinite S are caught otherwise (below).
    check(KSPSetTolerances(ksp, 1e-300, atol, kNoDivergenceTest, 10000), "KSPSetTolerances");
    check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
    check(KSPSetComputeEigenvalues(ksp, PETSC_TRUE), "KSPSetComputeEigenvalues");
  }

  std::vector<signed char> held_before;
  std::vector<PetscInt> rows;
  int iterations = 0;
  std::string failure;
  for (; iterations < max_iterations; ++iterations) {
    const std::vector<signed char> held = held_set(q, D);
    // the held set is the last one: X solves the QP (`iterations`, alike on every rank,
    // guards the collective test: a rank may hold no rows)
    if (iterations > 0 && same_on_every_rank(held, held_before)) break;
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
    if (saddle) {
      failure = solve_saddle(q, held, rows, b, X_held, settings.saddle_rows);
      if (!failure.empty()) break;
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
    // The scale came from r and the bounds, before X was known: a bound far from X (a
    // contact vertex far from its obstacle) can exceed ‖X‖∞ by orders.  With X known,
    // CG goes on from it to the tolerance of the test's own scale.
    for (int again = 0; again < 2 && reason >= 0; ++again) {
      const double needed = 1e-2 * settings.tol * min_d * kkt_scale(q, D);
      if (needed >= atol) break;
      atol = needed;
      check(KSPSetTolerances(ksp, 1e-300, atol, kNoDivergenceTest, 10000), "KSPSetTolerances");
      check(KSPSolve(ksp, b, q.X), "KSPSolve");
      check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
    }
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
  // (the same on every rank: the reason and the held-set test are global)
  if (!failure.empty()) throw NumericalError(failure);
  return iterations;
}

}  // namespace cdyn::petsc
