// test_petsc_step_solvers.cpp — the step solvers of the PETSc back end
// (qp/petsc/backend.hpp) against the native pdas, on one process and on two.
//
// Run by mpirun (tests/mpi/CMakeLists.txt): rank 0 runs the tests, the other ranks serve
// its collective solves, as in `mpirun -n 2 cdyn run`.  The QP is an obstacle problem
// of the membrane's kind: S = K + c I (K the 5-point Laplacian on an m × m grid, c the
// mass over dt²), a load pushing down onto a bowl-shaped obstacle, so that about a third
// of the unknowns rest on it; every solver must return the native pdas's solution to
// within the KKT tolerance's effect (‖ΔX‖∞ ≤ 1e-8 ‖X‖∞ at tol = 1e-12) with a KKT
// residual ≤ tol measured by the kernel's one measure (qp/kkt.hpp).  The same problem in
// saddle form (the pairs whose velocity space is continuous) against the native pdas.
#include <gtest/gtest.h>

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "cdyn/qp/step_solver.hpp"

namespace cdyn {
namespace {

constexpr double kTol = 1e-12;

// The obstacle QP on an m × m grid; `scale` multiplies S and r (a new matrix, same solution).
BoundQP obstacle_qp(int m, double scale = 1.0, bool upper_bounds = false) {
  const int n = m * m;
  const double h = 1.0 / (m + 1), c = 4.0;  // c: the mass term, S = K + c I
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int i, int j) { return i * m + j; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      t.emplace_back(id(i, j), id(i, j), scale * (4.0 + c * h * h));
      for (auto [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        if (i + di >= 0 && i + di < m && j + dj >= 0 && j + dj < m)
          t.emplace_back(id(i, j), id(i + di, j + dj), -scale * 1.0);
    }
  BoundQP qp;
  qp.S.resize(n, n);
  qp.S.setFromTriplets(t.begin(), t.end());
  qp.r = Eigen::VectorXd::Constant(n, -scale * 10.0 * h * h);
  qp.lower.resize(n);
  qp.upper = Eigen::VectorXd::Constant(n, INFINITY);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double x = (i + 1) * h - 0.5, y = (j + 1) * h - 0.5;
      qp.lower[id(i, j)] = -0.3 + 0.4 * (x * x + y * y);  // a bowl below the membrane's rim
      if (upper_bounds && (i + j) % 7 == 0) qp.upper[id(i, j)] = qp.lower[id(i, j)] + 0.01;
    }
  return qp;
}

QPResult native(const BoundQP& qp) {
  QPOptions o;
  o.tol = kTol;
  return make_step_solver("pdas", o)->solve(qp);
}

std::unique_ptr<StepSolver> distributed(const std::string& name, const std::string& pc = "") {
  QPOptions o;
  o.tol = kTol;
  return petsc::make_petsc_step_solver(name, o, pc);
}

void expect_same(const QPResult& got, const QPResult& want, const BoundQP& qp, const std::string& what) {
  ASSERT_TRUE(got.converged) << what;
  EXPECT_LE(kkt_residual(qp, got.X), kTol) << what;
  EXPECT_LE((got.X - want.X).lpNorm<Eigen::Infinity>(), 1e-8 * want.X.lpNorm<Eigen::Infinity>()) << what;
  EXPECT_EQ(got.active, want.active) << what;
}

TEST(PetscStepSolvers, EverySolverGivesTheNativeSolution) {
  const BoundQP qp = obstacle_qp(30);
  const QPResult want = native(qp);
  ASSERT_GT(want.active.size(), 100u);  // a real contact set
  ASSERT_LT(want.active.size(), 600u);
  for (const std::string name : {"pdas", "tao_tron", "tao_gpcg", "tao_bqnls", "tao_bncg", "snesvi"})
    expect_same(distributed(name)->solve(qp), want, qp, name);
  for (const std::string pc : {"gamg", "hypre"}) expect_same(distributed("pdas", pc)->solve(qp), want, qp, "pdas " + pc);
  expect_same(distributed("tao_tron", "hypre")->solve(qp), want, qp, "tao_tron hypre");
}

TEST(PetscStepSolvers, LowerAndUpperBounds) {
  const BoundQP qp = obstacle_qp(24, 1.0, /*upper_bounds=*/true);
  const QPResult want = native(qp);
  int at_upper = 0;
  for (int i : want.active) at_upper += want.X[i] == qp.upper[i];
  ASSERT_GT(at_upper, 5);
  for (const std::string name : {"pdas", "tao_tron", "snesvi"}) expect_same(distributed(name)->solve(qp), want, qp, name);
}

// A new S (dt changed) is sent again; a warm start from the solution takes one solve.
TEST(PetscStepSolvers, NewMatrixAndWarmStart) {
  const BoundQP qp1 = obstacle_qp(20), qp2 = obstacle_qp(20, 3.0);
  const QPResult want = native(qp1);
  auto solver = distributed("pdas");
  const QPResult first = solver->solve(qp1);
  expect_same(first, want, qp1, "qp1");
  expect_same(solver->solve(qp2), want, qp2, "qp2 (S scaled: the same solution)");
  const QPResult warm = solver->solve(qp1, &first);
  expect_same(warm, want, qp1, "warm");
  EXPECT_EQ(warm.iterations, 1);
}

// Two solvers take turns on the ranks: each solve sends its own S.
TEST(PetscStepSolvers, TwoSolversTakeTurns) {
  const BoundQP a = obstacle_qp(16), b = obstacle_qp(22, 2.0, true);
  const QPResult want_a = native(a), want_b = native(b);
  auto sa = distributed("pdas"), sb = distributed("snesvi", "jacobi");
  expect_same(sa->solve(a), want_a, a, "a");
  expect_same(sb->solve(b), want_b, b, "b");
  expect_same(sa->solve(a), want_a, a, "a again");
  sa->clear();
  expect_same(sa->solve(a), want_a, a, "a after clear");
}

TEST(PetscStepSolvers, IndefiniteMatrixIsANumericalFailure) {
  BoundQP qp;
  qp.S.resize(2, 2);
  std::vector<Eigen::Triplet<double>> t{{0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 2.0}, {1, 1, 1.0}};  // eigenvalues 3, −1
  qp.S.setFromTriplets(t.begin(), t.end());
  qp.r = Eigen::Vector2d(1.0, -1.0);  // along the negative eigenvector
  qp.lower = Eigen::Vector2d::Constant(-INFINITY);
  qp.upper = Eigen::Vector2d::Constant(INFINITY);
  EXPECT_THROW(distributed("pdas", "jacobi")->solve(qp), NumericalError);
  // and the ranks go on serving after it
  const BoundQP ok = obstacle_qp(10);
  expect_same(distributed("pdas")->solve(ok), native(ok), ok, "after the failure");
}

// A diagonal entry ≤ 0: S is not positive definite, found before any Krylov solve (the
// solve's work vectors, made before the test, are freed on the way out:
// mpi_step_solvers_free_their_objects).  The next solver, a new object with an S of
// the same size, must send its own S (found: a new solver made at the destroyed one's
// address took the distributed S for its own and solved with the bad one).
TEST(PetscStepSolvers, NonPositiveDiagonalIsANumericalFailure) {
  BoundQP qp = obstacle_qp(10);
  qp.S.coeffRef(17, 17) = -1.0;
  EXPECT_THROW(distributed("pdas")->solve(qp), NumericalError);
  const BoundQP ok = obstacle_qp(10);
  expect_same(distributed("pdas")->solve(ok), native(ok), ok, "after the failure");
}

// The obstacle QP in saddle form (qp/bound_qp.hpp): A the Laplacian, C a mass matrix's
// kind (the 5-point pattern, h² on the diagonal and h²/8 off it: SPD), B = C, c = 4, so
// S = A + c Bᵀ C⁻¹ B = A + c C; the bounds and the load are obstacle_qp's.
BoundQP saddle_obstacle_qp(int m, bool upper_bounds = false) {
  BoundQP qp = obstacle_qp(m, 1.0, upper_bounds);
  const double h = 1.0 / (m + 1);
  SaddleForm f;
  f.A = qp.S;
  f.A.diagonal().setConstant(4.0);
  f.C = qp.S;
  for (int j = 0; j < f.C.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(f.C, j); it; ++it) it.valueRef() = (it.row() == j ? 1.0 : 0.125) * h * h;
  f.B = f.C;
  f.c = 4.0;
  qp.saddle = f;
  qp.S.resize(0, 0);
  return qp;
}

// In saddle form the distributed pdas factorizes each reduced saddle system by MUMPS;
// it must return the native pdas's solution (whose LU is UMFPACK's), with lower and
// upper bounds, and take one solve from a warm start at the solution.
TEST(PetscStepSolvers, SaddleFormGivesTheNativeSolution) {
  for (const bool upper_bounds : {false, true}) {
    const BoundQP qp = saddle_obstacle_qp(24, upper_bounds);
    const QPResult want = native(qp);
    ASSERT_GT(want.active.size(), 60u);
    auto solver = distributed("pdas");
    const QPResult first = solver->solve(qp);
    expect_same(first, want, qp, upper_bounds ? "saddle, upper bounds" : "saddle");
    const QPResult warm = solver->solve(qp, &first);
    expect_same(warm, want, qp, "saddle, warm");
    EXPECT_EQ(warm.iterations, 1);
  }
}

// S = A + c Bᵀ C⁻¹ B indefinite (A's eigenvalues 3 and −1, c C⁻¹ = 0.1 I): the saddle
// matrix's inertia shows it, a NumericalError, and the ranks go on serving.
TEST(PetscStepSolvers, IndefiniteSaddleFormIsANumericalFailure) {
  BoundQP qp;
  SaddleForm f;
  std::vector<Eigen::Triplet<double>> t{{0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 2.0}, {1, 1, 1.0}};
  f.A.resize(2, 2);
  f.A.setFromTriplets(t.begin(), t.end());
  f.B = SparseMatrix(2, 2);
  f.B.setIdentity();
  f.C = f.B;
  f.c = 0.1;
  qp.saddle = f;
  qp.r = Eigen::Vector2d(1.0, -1.0);
  qp.lower = Eigen::Vector2d::Constant(-INFINITY);
  qp.upper = Eigen::Vector2d::Constant(INFINITY);
  EXPECT_THROW(distributed("pdas")->solve(qp), NumericalError);
  const BoundQP ok = saddle_obstacle_qp(10);
  expect_same(distributed("pdas")->solve(ok), native(ok), ok, "after the failure");
}

TEST(PetscStepSolvers, RefusesWhatItCannotTake) {
  EXPECT_THROW(distributed("ipopt"), InputError);
  EXPECT_THROW(distributed("pdas", "ilu"), InputError);
  EXPECT_THROW(distributed("tao_tron", "gamg"), InputError);  // systems of changing size
  const BoundQP saddle = saddle_obstacle_qp(4);
  EXPECT_THROW(distributed("tao_tron")->solve(saddle), InputError);  // needs S explicitly
  EXPECT_THROW(distributed("pdas", "jacobi")->solve(saddle), InputError);  // a factorization: no pc
}

}  // namespace
}  // namespace cdyn

// Rank 0 runs the tests; the others serve its solves until it says quit.
int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  cdyn::petsc::initialize();
  if (cdyn::petsc::rank() != 0) return cdyn::petsc::end_process(cdyn::petsc::serve());
  std::printf("on %d MPI process%s\n", cdyn::petsc::size(), cdyn::petsc::size() == 1 ? "" : "es");
  return cdyn::petsc::end_process(RUN_ALL_TESTS());
}
