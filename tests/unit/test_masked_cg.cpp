// test_masked_cg.cpp — preconditioned CG with a held set (linalg/masked_cg.hpp) against a
// dense solve of the reduced system S_II y_I = b_I.
//
// The reference is mathematics: with the held rows set to b and the free block solved
// exactly (dense LDLᵀ), y is the unique solution of S̃y = b.  CG must
//  - leave y_A = b_A exactly,
//  - stop with the true scaled residual max_{i∉A} |b − S̃y|_i / S_ii at or below tol (recomputed
//    here from scratch, not CG's updated residual), and report it,
//  - be within the error bound that residual implies: ‖y − y*‖_∞ ≤ ‖(D^-1 S_II)^-1‖_∞ · tol,
//  - converge in at most |I| iterations on a well-conditioned matrix (CG's finite termination).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "cdyn/linalg/masked_cg.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// A random sparse SPD matrix: 1D Laplacian-like chain plus random symmetric couplings,
// made strictly diagonally dominant (so κ(D⁻¹S) is modest and CG needs few iterations).
cdyn::SparseMatrix random_spd(int n, std::mt19937& gen) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  MatrixXd S = MatrixXd::Zero(n, n);
  for (int i = 0; i + 1 < n; ++i) S(i, i + 1) = S(i + 1, i) = -1.0 + 0.3 * U(gen);
  for (int k = 0; k < n; ++k) {
    const int i = static_cast<int>((U(gen) + 1.0) * 0.5 * (n - 1)), j = static_cast<int>((U(gen) + 1.0) * 0.5 * (n - 1));
    if (i != j) S(i, j) = S(j, i) = 0.5 * U(gen);
  }
  for (int i = 0; i < n; ++i) S(i, i) = S.row(i).cwiseAbs().sum() + 0.5 + (U(gen) + 1.0);
  cdyn::SparseMatrix s = S.sparseView();
  s.makeCompressed();
  return s;
}

// mostly_held: three rows in four held instead of one, so that CG iterates on the free
// rows alone (masked_cg.cpp: fewer than half of the rows free).
void solves_the_reduced_system_to_its_scaled_residual(bool mostly_held) {
  std::mt19937 gen(3);
  const int n = 60;
  const cdyn::SparseMatrix S = random_spd(n, gen);
  const MatrixXd Sd(S);
  const VectorXd D = Sd.diagonal();
  std::vector<char> held(n, 0);
  for (int i = 0; i < n; ++i) held[i] = (i % 4 == 0) != mostly_held;
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = U(gen);

  // dense reference on I
  std::vector<int> I;
  for (int i = 0; i < n; ++i)
    if (!held[i]) I.push_back(i);
  const int m = static_cast<int>(I.size());
  MatrixXd SII(m, m);
  VectorXd bI(m);
  for (int a = 0; a < m; ++a) {
    bI[a] = b[I[a]];
    for (int c = 0; c < m; ++c) SII(a, c) = Sd(I[a], I[c]);
  }
  const VectorXd yI = SII.ldlt().solve(bI);
  MatrixXd DinvS = SII;
  for (int a = 0; a < m; ++a) DinvS.row(a) /= SII(a, a);
  const double inverse_norm = DinvS.inverse().cwiseAbs().rowwise().sum().maxCoeff();  // ‖(D⁻¹S_II)⁻¹‖_∞

  // One iteration object for all solves, first used with nothing held: its work vectors
  // then hold values on the rows this test holds.
  cdyn::MaskedCG cg(S);
  VectorXd y_other;
  ASSERT_TRUE(cg.solve(std::vector<char>(n, 0), b, y_other, 1e-12, 200).converged);
  for (const double tol : {1e-4, 1e-10, 1e-14}) {
    VectorXd y = VectorXd::Constant(n, 0.3);  // a first guess of the wrong values on A too
    const cdyn::MaskedCGResult res = cg.solve(held, b, y, tol, 200);
    ASSERT_TRUE(res.converged) << tol;
    EXPECT_LE(res.iterations, m) << tol;
    double scaled = 0.0, error = 0.0;
    for (int a = 0; a < m; ++a) {
      double Sy = 0.0;
      for (int c = 0; c < m; ++c) Sy += SII(a, c) * y[I[c]];
      scaled = std::max(scaled, std::abs(bI[a] - Sy) / SII(a, a));
      error = std::max(error, std::abs(y[I[a]] - yI[a]));
    }
    for (int i = 0; i < n; ++i) {
      if (held[i]) {
        EXPECT_EQ(y[i], b[i]);
      }
    }
    // The true residual may exceed CG's updated one by round-off: ~ε ‖D⁻¹S‖ ‖y‖ per
    // iteration, below 1e-15 here.
    EXPECT_LE(scaled, tol + 1e-15) << tol;
    EXPECT_NEAR(res.scaled_residual, scaled, 1e-15) << tol;
    EXPECT_LE(error, inverse_norm * (tol + 1e-15)) << tol;
  }

  // From the solution itself: no iteration.
  VectorXd y = VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) y[i] = b[i];
  for (int a = 0; a < m; ++a) y[I[a]] = yI[a];
  const cdyn::MaskedCGResult again = cdyn::masked_cg(S, held, b, y, 1e-12, 200);
  EXPECT_TRUE(again.converged);
  EXPECT_EQ(again.iterations, 0);
}

TEST(MaskedCG, SolvesTheReducedSystemToItsScaledResidual) { solves_the_reduced_system_to_its_scaled_residual(false); }
TEST(MaskedCG, SolvesTheReducedSystemOnItsFreeRowsWhenMostAreHeld) {
  solves_the_reduced_system_to_its_scaled_residual(true);
}

TEST(MaskedCG, ReportsAMissedToleranceWithinTheCap) {
  std::mt19937 gen(5);
  const int n = 40;
  const cdyn::SparseMatrix S = random_spd(n, gen);
  const VectorXd D = MatrixXd(S).diagonal();
  const std::vector<char> held(n, 0);
  const VectorXd b = VectorXd::Ones(n);
  VectorXd y;
  const cdyn::MaskedCGResult res = cdyn::masked_cg(S, held, b, y, 1e-14, 2);
  EXPECT_FALSE(res.converged);
  EXPECT_EQ(res.iterations, 2);
  EXPECT_GT(res.scaled_residual, 1e-14);
}

}  // namespace

namespace {

// resume: the iteration interrupted at a loose tolerance and continued to a tight one
// performs the same floating-point operations as one uninterrupted solve, so it ends
// with the same iterate bit for bit after the same number of iterations.
// (mostly_held: four rows in five held, CG on the free rows alone)
void resuming_is_the_uninterrupted_iteration(bool mostly_held) {
  std::mt19937 gen(7);
  const int n = 80;
  const cdyn::SparseMatrix S = random_spd(n, gen);
  std::vector<char> held(n, 0);
  for (int i = 0; i < n; ++i) held[i] = (i % 5 == 1) != mostly_held;
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = U(gen);

  VectorXd y_once;
  cdyn::MaskedCG once(S);
  const cdyn::MaskedCGResult whole = once.solve(held, b, y_once, 1e-13, 200);
  ASSERT_TRUE(whole.converged);

  VectorXd y;
  cdyn::MaskedCG twice(S);
  const cdyn::MaskedCGResult loose = twice.solve(held, b, y, 1e-4, 200);
  ASSERT_TRUE(loose.converged);
  ASSERT_GT(loose.iterations, 0);
  const cdyn::MaskedCGResult tight = twice.solve(held, b, y, 1e-13, 200, /*resume=*/true);
  ASSERT_TRUE(tight.converged);
  EXPECT_EQ(loose.iterations + tight.iterations, whole.iterations);
  EXPECT_EQ(tight.scaled_residual, whole.scaled_residual);
  for (int i = 0; i < n; ++i) EXPECT_EQ(y[i], y_once[i]) << i;
  // the residual it reports is b − S̃y up to CG's round-off
  const VectorXd Sy = MatrixXd(S) * y.cwiseProduct(VectorXd::NullaryExpr(n, [&](Eigen::Index i) { return held[i] ? 0.0 : 1.0; }));
  for (int i = 0; i < n; ++i)
    if (!held[i]) {
      EXPECT_NEAR(twice.residual()[i], b[i] - Sy[i], 1e-12) << i;
    }
}

TEST(MaskedCG, ResumingIsTheUninterruptedIteration) { resuming_is_the_uninterrupted_iteration(false); }
TEST(MaskedCG, ResumingOnTheFreeRowsIsTheUninterruptedIteration) { resuming_is_the_uninterrupted_iteration(true); }

// One iteration object serves the PDAS iterates of a whole time loop, each with its held
// set.  On the free rows alone it clears only the rows its last such solve wrote: a solve
// must then give the bits of a fresh object's, whatever sets came before (here two with
// most rows held, then one with most free, then the first again).
TEST(MaskedCG, AReusedIterationGivesTheBitsOfAFreshOne) {
  std::mt19937 gen(11);
  const int n = 90;
  const cdyn::SparseMatrix S = random_spd(n, gen);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = U(gen);
  auto held_every = [&](int period, int offset, bool most) {
    std::vector<char> held(n);
    for (int i = 0; i < n; ++i) held[i] = (i % period == offset) != most;
    return held;
  };
  const std::vector<std::vector<char>> sets = {held_every(5, 0, true), held_every(4, 1, true), held_every(3, 2, false),
                                               held_every(5, 0, true)};
  cdyn::MaskedCG reused(S);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    VectorXd y_reused = VectorXd::Constant(n, 0.1), y_fresh = y_reused;
    const cdyn::MaskedCGResult a = reused.solve(sets[k], b, y_reused, 1e-12, 200);
    const cdyn::MaskedCGResult f = cdyn::MaskedCG(S).solve(sets[k], b, y_fresh, 1e-12, 200);
    ASSERT_TRUE(a.converged) << k;
    EXPECT_EQ(a.iterations, f.iterations) << k;
    EXPECT_EQ(a.scaled_residual, f.scaled_residual) << k;
    for (int i = 0; i < n; ++i) EXPECT_EQ(y_reused[i], y_fresh[i]) << k << " " << i;
  }
}

}  // namespace
