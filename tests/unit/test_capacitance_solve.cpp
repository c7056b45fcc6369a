// test_capacitance_solve.cpp — qp/pdas/capacitance_solve.hpp: S̃ y = b for a few held
// unknowns from S's own factor and the capacitance matrix K = E_Aᵀ S⁻¹ E_A.
//
// The identity: y_A = b_A and S_II y_I = b_I, the solution of S̃ (S with the held rows and
// columns replaced by the identity's), asserted against CHOLMOD's factor of S̃ itself.
// Both are exact up to round-off; on the shifted Laplacian (condition < 3) and on an
// unshifted one (the reconstruction's stiffness kind, condition 10³–10⁴ on 40 × 40 and
// 120 × 120 grids) the two agree to 1e-14 and 1e-13 relative (measured: at most 4.5e-16
// and 3.2e-15).
#include <gtest/gtest.h>

#include <vector>

#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/qp/pdas/capacitance_solve.hpp"
#include "cdyn/qp/pdas/reduced_system.hpp"
#include "grid_fixtures.hpp"

namespace {

using cdyn::SparseMatrix;
using Eigen::VectorXd;

// y with S̃ y = b, S̃ factorized by CHOLMOD.
VectorXd reference(const SparseMatrix& S, const std::vector<int>& held, const VectorXd& b) {
  cdyn::HeldSet mask(S.rows(), 0);
  for (int i : held) mask[i] = 1;
  SparseMatrix S_tilde = S;
  cdyn::replace_held_by_identity(S, mask, S_tilde);
  cdyn::SparseCholesky chol;
  chol.analyze(S_tilde);
  EXPECT_LT(chol.factorize(S_tilde), 0);
  return chol.solve(b);
}

// Three held sets on a k × k grid, each against the factor of S̃ itself.
void check_held_sets(int k, double shift) {
  const int n = k * k;
  const SparseMatrix S = grid_laplacian(k, 4.0 + shift);
  cdyn::SparseCholesky chol;
  chol.analyze(S);
  ASSERT_LT(chol.factorize(S), 0);
  cdyn::CapacitanceSolve capacitance;
  const VectorXd b = VectorXd::LinSpaced(n, -2.0, 5.0).array().cos();
  // a lone unknown, a cluster of neighbours (K's nearly equal columns), and a set that
  // shares columns with the last (the kept ones reused)
  const std::vector<std::vector<int>> sets = {
      {n / 2}, {30, 17 * k + 10, 17 * k + 11, 18 * k + 10, 18 * k + 11}, {30, 17 * k + 11, n - 1}};
  for (const auto& held : sets) {
    bool ok = false;
    const double flops = capacitance.hold(chol, held, ok);
    ASSERT_TRUE(ok);
    EXPECT_GT(flops, 0.0);
    VectorXd y;
    capacitance.solve(chol, b, y);
    const VectorXd expected = reference(S, held, b);
    const double tol = shift > 0 ? 1e-14 : 1e-13;
    EXPECT_LE((y - expected).lpNorm<Eigen::Infinity>(), tol * expected.lpNorm<Eigen::Infinity>())
        << k << " × " << k << ", shift " << shift << ", " << held.size() << " held";
    for (int i : held) EXPECT_EQ(y[i], b[i]);
  }
  EXPECT_EQ(capacitance.missing({30, n - 1, n / 2}), 0);  // every column made once, kept
  EXPECT_EQ(capacitance.missing({31}), 1);
  bool ok = false;
  EXPECT_EQ(capacitance.hold(chol, {30, 17 * k + 11, n - 1}, ok), 0.0);  // the same set: K as it is
  EXPECT_TRUE(ok);
  capacitance.clear();
  EXPECT_EQ(capacitance.missing({30}), 1);
}

TEST(CapacitanceSolve, SolvesTheReducedSystemWithTheFactorOfS) {
  // (CHOLMOD leaves the factor of the 40 × 40 grid simplicial and makes the 120 × 120
  // one's supernodal: both kinds of unit_forward)
  for (const int k : {40, 120})
    for (const double shift : {4.0, 0.0}) check_held_sets(k, shift);
}

TEST(CapacitanceSolve, KeepsAtMostTheFactorsEntriesInColumns) {
  // A contact zone that wanders over the whole grid: every unknown held in turn.  The
  // columns kept never take more entries than L; past that the old ones are dropped,
  // and the solves stay right.
  const int k = 40, n = k * k;
  const SparseMatrix S = grid_laplacian(k, 8.0);
  cdyn::SparseCholesky chol;
  chol.analyze(S);
  ASSERT_LT(chol.factorize(S), 0);
  cdyn::CapacitanceSolve capacitance;
  bool ok = false;
  for (int i = 0; i < n; ++i) capacitance.hold(chol, {i}, ok);
  EXPECT_EQ(capacitance.missing({0}), 1);      // dropped
  EXPECT_EQ(capacitance.missing({n - 1}), 0);  // the last set's
  EXPECT_LE(capacitance.stored_entries(), chol.solve_flops() / 4.0);
  const std::vector<int> held = {0, n / 2, n - 1};
  capacitance.hold(chol, held, ok);
  ASSERT_TRUE(ok);
  const VectorXd b = VectorXd::LinSpaced(n, -2.0, 5.0).array().cos();
  VectorXd y;
  capacitance.solve(chol, b, y);
  const VectorXd expected = reference(S, held, b);
  EXPECT_LE((y - expected).lpNorm<Eigen::Infinity>(), 1e-14 * expected.lpNorm<Eigen::Infinity>());
}

}  // namespace
