// test_sparse_cholesky.cpp — linalg/sparse_cholesky.hpp: the analysis with a given
// fill-reducing order, which the active-set solver uses for the free block S_II of
// resting contact (the order of I induced by S's own analysis), a factor kept aside
// and taken back (the active-set solver's return to S's own factor), and the halves of a
// solve with a unit vector's path (the capacitance solve's parts).
//
// Any symmetric permutation P gives the factorization P S Pᵀ = L Lᵀ of the same S, so
// the solution of S x = b must not depend on the order beyond round-off: asserted to
// 1e-12 relative on a shifted 5-point Laplacian whose condition is below 10.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/sparse_cholesky.hpp"
#include "grid_fixtures.hpp"

namespace {

using cdyn::SparseMatrix;
using Eigen::VectorXd;

// 4 I + the 5-point Laplacian of a k × k grid: eigenvalues in (4, 12), condition < 3.
SparseMatrix shifted_laplacian(int k) { return grid_laplacian(k, 8.0); }

TEST(SparseCholesky, AGivenOrderingSolvesTheSameSystem) {
  const int k = 30, n = k * k;
  const SparseMatrix S = shifted_laplacian(k);
  const VectorXd b = VectorXd::LinSpaced(n, -1.0, 2.0);
  cdyn::SparseCholesky by_amd, given;
  by_amd.analyze(S);
  ASSERT_LT(by_amd.factorize(S), 0);
  std::vector<int> reversed(n);
  std::iota(reversed.rbegin(), reversed.rend(), 0);
  given.analyze(S, reversed);
  ASSERT_LT(given.factorize(S), 0);
  const VectorXd x = by_amd.solve(b), y = given.solve(b);
  EXPECT_LE((S * y - b).lpNorm<Eigen::Infinity>(), 1e-12 * b.lpNorm<Eigen::Infinity>());
  EXPECT_LE((x - y).lpNorm<Eigen::Infinity>(), 1e-12 * x.lpNorm<Eigen::Infinity>());
  // the order used is a permutation of the unknowns (CHOLMOD postorders the given one)
  std::vector<int> order = given.ordering();
  std::sort(order.begin(), order.end());
  std::vector<int> identity(n);
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(order, identity);
  // the lexicographic order of a grid is a band order, which fills the band: more work
  // than the minimum degree order (k³ against about k² log k)
  EXPECT_GT(given.factorization_flops(), by_amd.factorization_flops());
}

TEST(SparseCholesky, AnOrderingOfTheWrongLengthIsRefused) {
  const SparseMatrix S = shifted_laplacian(4);
  cdyn::SparseCholesky chol;
  EXPECT_THROW(chol.analyze(S, std::vector<int>(15, 0)), cdyn::InputError);
}

// A factorization that breaks down drops the factor: a solve after it is refused, not a
// null dereference.
TEST(SparseCholesky, ASolveWithoutAFactorIsRefused) {
  const SparseMatrix S = shifted_laplacian(4);
  SparseMatrix indefinite = -S;
  cdyn::SparseCholesky chol;
  chol.analyze(indefinite);
  EXPECT_GE(chol.factorize(indefinite), 0);
  EXPECT_FALSE(chol.factorized());
  EXPECT_THROW(chol.solve(VectorXd::Ones(16)), cdyn::InputError);
}

// A kept factor is a copy: row updates and a factorization of another matrix leave it as
// it was, and taking it back gives the solves of the original factor, bit for bit.
TEST(SparseCholesky, AKeptFactorComesBackAsItWas) {
  const int k = 20, n = k * k;
  const SparseMatrix S = shifted_laplacian(k);
  const VectorXd b = VectorXd::LinSpaced(n, -1.0, 3.0).array().sin();
  cdyn::SparseCholesky chol;
  chol.analyze(S);
  ASSERT_LT(chol.factorize(S), 0);
  const VectorXd x = chol.solve(b);
  EXPECT_FALSE(chol.has_kept());
  chol.keep();
  EXPECT_TRUE(chol.has_kept());
  for (int i = 0; i < n; i += 7) chol.replace_by_identity(i);
  EXPECT_GT((chol.solve(b) - x).norm(), 1e-3 * x.norm());  // the factor did change
  chol.use_kept();
  VectorXd again = chol.solve(b);
  EXPECT_EQ(again, x);
  ASSERT_LT(chol.factorize(SparseMatrix(2.0 * S)), 0);
  chol.use_kept();  // (and the copy can be taken again)
  again = chol.solve(b);
  EXPECT_EQ(again, x);
  chol.forget_kept();
  EXPECT_FALSE(chol.has_kept());
  EXPECT_THROW(chol.use_kept(), cdyn::InputError);
  chol.keep();
  chol.analyze(S);  // a new analysis drops it
  EXPECT_FALSE(chol.has_kept());
}

// The two halves of a solve, and the forward half of a unit vector on its path alone:
// on a factor CHOLMOD makes supernodal (a 120 × 120 grid: our sweeps) and on one it
// leaves simplicial (a 6 × 6 grid: its columns walked one by one).
TEST(SparseCholesky, TheHalvesOfASolveAndAUnitVectorsPath) {
  for (const int k : {120, 6}) {
    const int n = k * k;
    const SparseMatrix S = shifted_laplacian(k);
    cdyn::SparseCholesky chol;
    chol.analyze(S);
    ASSERT_LT(chol.factorize(S), 0);
    ASSERT_TRUE(chol.has_halves());
    const VectorXd b = VectorXd::LinSpaced(n, -1.0, 3.0).array().sin();
    VectorXd v = b;
    chol.forward(v);
    chol.backward(v);
    const VectorXd x = chol.solve(b);
    EXPECT_LE((v - x).lpNorm<Eigen::Infinity>(), 1e-15 * x.lpNorm<Eigen::Infinity>()) << k;
    for (const int i : {0, n / 3, n - 1}) {
      std::vector<int> rows;
      std::vector<double> values;
      const double flops = chol.unit_forward(i, rows, values);
      VectorXd z = VectorXd::Unit(n, i);
      chol.forward(z);  // the whole sweep
      ASSERT_EQ(rows.size(), values.size());
      EXPECT_GT(flops, 0.0);
      EXPECT_TRUE(std::is_sorted(rows.begin(), rows.end()));
      VectorXd on_path = VectorXd::Zero(n);
      for (std::size_t p = 0; p < rows.size(); ++p) on_path[rows[p]] = values[p];
      // (the same operations on the path's entries; the others are exact zeros)
      EXPECT_LE((on_path - z).lpNorm<Eigen::Infinity>(), 1e-15 * z.lpNorm<Eigen::Infinity>()) << k << " " << i;
      if (k == 120) EXPECT_LT(rows.size(), static_cast<std::size_t>(n / 10));  // a path, not the whole
    }
  }
  cdyn::SparseCholesky chol;
  chol.analyze(shifted_laplacian(20));
  VectorXd v = VectorXd::Ones(400);
  EXPECT_THROW(chol.forward(v), cdyn::InputError);  // no factor yet
  ASSERT_LT(chol.factorize(shifted_laplacian(20)), 0);
  chol.replace_by_identity(3);  // (CHOLMOD makes it LDLᵀ)
  EXPECT_FALSE(chol.has_halves());
}

}  // namespace
