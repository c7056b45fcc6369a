// test_qp_solvers.cpp — the four step solvers (qp/bound_qp.hpp) on random SPD bound-constrained QPs.
//
// The reference answers come from mathematics, not from one of the solvers:
//  - small problems (n ≤ 8): exhaustive enumeration of the 3ⁿ active sets, each a dense
//    linear solve, keeping the one that satisfies the KKT conditions (the QP is strictly
//    convex, so exactly one does);
//  - larger problems: the a-posteriori error bound of the natural residual for a
//    strongly convex QP (Facchinei & Pang 2003, Prop. 6.3.1): in the scaled unknowns
//    y = D^½ X,  ‖y − y*‖₂ ≤ (1 + L)/μ ‖F_y‖₂  with μ, L the extreme eigenvalues of
//    D^-½ S D^-½ (computed densely here) and F_y = D^½ F.  Two solvers must agree within
//    the sum of their bounds, and each must have kkt_residual ≤ tol.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/step_solver.hpp"
#include "cdyn/qp/pdas/pdas.hpp"
#include "grid_fixtures.hpp"

namespace {

using cdyn::BoundQP;
using cdyn::QPOptions;
using cdyn::QPResult;
using cdyn::SparseMatrix;
using Eigen::MatrixXd;
using Eigen::VectorXd;
constexpr double inf = std::numeric_limits<double>::infinity();

// S = 5-point Laplacian of a k × k grid (or the 1D one, k × 1) + random diagonal
// shift, plus, if `mass`, a P1-like consistent mass term that has positive off-diagonal
// entries (so S is not an M-matrix, where plain PDAS is not guaranteed to converge).
SparseMatrix grid_matrix(int kx, int ky, std::mt19937& gen, bool mass) {
  std::uniform_real_distribution<double> shift(0.01, 1.0);
  const int n = kx * ky;
  std::vector<Eigen::Triplet<double>> t;
  auto id = [&](int i, int j) { return j * kx + i; };
  for (int j = 0; j < ky; ++j)
    for (int i = 0; i < kx; ++i) {
      const int p = id(i, j);
      double diag = shift(gen);
      auto link = [&](int q, double w) {
        t.emplace_back(p, q, -w);
        diag += w;
      };
      if (i > 0) link(id(i - 1, j), 1.0);
      if (i + 1 < kx) link(id(i + 1, j), 1.0);
      if (j > 0) link(id(i, j - 1), 1.0);
      if (j + 1 < ky) link(id(i, j + 1), 1.0);
      if (mass) {  // + 40 × (lumped-minus-consistent-like) term: 4/6 on the diagonal, 1/6 off
        const double m = 40.0;
        diag += m * 4.0 / 6.0;
        if (i > 0) t.emplace_back(p, id(i - 1, j), m / 6.0);
        if (i + 1 < kx) t.emplace_back(p, id(i + 1, j), m / 6.0);
      }
      t.emplace_back(p, p, diag);
    }
  SparseMatrix S(n, n);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

// r random; about half the unknowns get a lower bound, a quarter an upper bound,
// some both; all chosen so that many bounds are active at the solution.
BoundQP random_problem(int kx, int ky, unsigned seed, bool mass) {
  std::mt19937 gen(seed);
  BoundQP qp;
  qp.S = grid_matrix(kx, ky, gen, mass);
  const int n = kx * ky;
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  qp.r.resize(n);
  qp.lower = VectorXd::Constant(n, -inf);
  qp.upper = VectorXd::Constant(n, inf);
  for (int i = 0; i < n; ++i) {
    qp.r[i] = U(gen);
    const double kind = 0.5 * (U(gen) + 1.0);
    if (kind < 0.5) qp.lower[i] = 0.3 * U(gen) - 0.2;
    else if (kind < 0.75) qp.upper[i] = 0.3 * U(gen) + 0.2;
    else if (kind < 0.85) {
      qp.lower[i] = -0.1 + 0.05 * U(gen);
      qp.upper[i] = 0.1 + 0.05 * U(gen);
    }
  }
  return qp;
}

// Exhaustive solution of a small strictly convex bound QP (n ≤ 8): every assignment
// free / lower / upper, dense solve, KKT check.
VectorXd brute_force(const BoundQP& qp) {
  const int n = qp.size();
  const MatrixXd S(qp.S);
  int total = 1;
  for (int i = 0; i < n; ++i) total *= 3;
  for (int code = 0; code < total; ++code) {
    std::vector<int> st(n);
    int c = code;
    bool ok = true;
    for (int i = 0; i < n; ++i) {
      st[i] = c % 3;
      c /= 3;
      if ((st[i] == 1 && !std::isfinite(qp.lower[i])) || (st[i] == 2 && !std::isfinite(qp.upper[i]))) ok = false;
    }
    if (!ok) continue;
    VectorXd X = VectorXd::Zero(n);
    std::vector<int> free;
    for (int i = 0; i < n; ++i) {
      if (st[i] == 1) X[i] = qp.lower[i];
      else if (st[i] == 2) X[i] = qp.upper[i];
      else free.push_back(i);
    }
    const int f = static_cast<int>(free.size());
    if (f > 0) {
      MatrixXd Sff(f, f);
      VectorXd b(f);
      for (int a = 0; a < f; ++a) {
        b[a] = qp.r[free[a]] - S.row(free[a]).dot(X);
        for (int bb = 0; bb < f; ++bb) Sff(a, bb) = S(free[a], free[bb]);
      }
      const VectorXd y = Sff.ldlt().solve(b);
      for (int a = 0; a < f; ++a) X[free[a]] = y[a];
    }
    const VectorXd lam = S * X - qp.r;
    const double eps = 1e-12;
    bool kkt = true;
    for (int i = 0; i < n && kkt; ++i) {
      if (st[i] == 0) kkt = X[i] >= qp.lower[i] - eps && X[i] <= qp.upper[i] + eps;
      if (st[i] == 1) kkt = lam[i] >= -eps;
      if (st[i] == 2) kkt = lam[i] <= eps;
    }
    if (kkt) return X;
  }
  ADD_FAILURE() << "brute force found no KKT point";
  return VectorXd::Zero(n);
}

// The a-posteriori bound on ‖X − X*‖_∞ (see the file header).
struct ErrorBound {
  VectorXd D;
  double factor = 0;  // max_i D_i^-½ · (1 + L)/μ
  explicit ErrorBound(const BoundQP& qp) {
    D = cdyn::scaling_diagonal(qp);
    const VectorXd s = D.cwiseSqrt().cwiseInverse();
    const MatrixXd Shat = s.asDiagonal() * MatrixXd(qp.S) * s.asDiagonal();
    Eigen::SelfAdjointEigenSolver<MatrixXd> eig(Shat, Eigen::EigenvaluesOnly);
    const double mu = eig.eigenvalues().minCoeff(), L = eig.eigenvalues().maxCoeff();
    factor = s.maxCoeff() * (1.0 + L) / mu;
  }
  double operator()(const BoundQP& qp, const QPResult& res) const {
    const VectorXd F = cdyn::natural_residual(qp, res.X, res.reaction, D);
    return factor * (D.cwiseSqrt().cwiseProduct(F)).norm();
  }
};

// Every solver's result satisfies the KKT conditions with the right signs.
void expect_kkt(const BoundQP& qp, const QPResult& res, double tol, const std::string& who) {
  EXPECT_TRUE(res.converged) << who;
  EXPECT_LE(res.kkt_residual, tol) << who;
  EXPECT_NEAR(cdyn::kkt_residual(qp, res.X), res.kkt_residual, 1e-3 * tol) << who;
  const double scale = std::max(res.X.lpNorm<Eigen::Infinity>(), 1.0);
  for (int i = 0; i < qp.size(); ++i) {
    EXPECT_GE(res.X[i], qp.lower[i] - tol * scale) << who << " i=" << i;
    EXPECT_LE(res.X[i], qp.upper[i] + tol * scale) << who << " i=" << i;
  }
  const VectorXd D = cdyn::scaling_diagonal(qp);
  // the reaction is S X − r (PDAS updates it from iterate to iterate on the rows held at
  // both: round-off of the product's size) and the active list is the rule's at it
  if (!qp.saddle) {
    const VectorXd gradient = qp.S * res.X - qp.r;
    const double terms = (qp.S.cwiseAbs() * res.X.cwiseAbs()).maxCoeff() + qp.r.lpNorm<Eigen::Infinity>();
    EXPECT_LE((res.reaction - gradient).lpNorm<Eigen::Infinity>(), 1e-13 * terms) << who;
  }
  EXPECT_EQ(res.active, cdyn::active_set(qp, res.X, res.reaction, D)) << who;
  std::vector<char> is_active(qp.size(), 0);
  for (int i : res.active) is_active[i] = 1;
  for (int i = 0; i < qp.size(); ++i) {
    const double lam = res.reaction[i] / D[i];  // in units of X
    if (!is_active[i]) {
      EXPECT_LE(std::abs(lam), 2 * tol * scale) << who << " free i=" << i;
    } else if (std::abs(res.X[i] - qp.lower[i]) <= std::abs(res.X[i] - qp.upper[i])) {
      EXPECT_GE(lam, -2 * tol * scale) << who << " lower i=" << i;  // pushes up
    } else {
      EXPECT_LE(lam, 2 * tol * scale) << who << " upper i=" << i;   // pushes down
    }
  }
}

TEST(QPSolvers, SmallProblemsMatchExhaustiveEnumeration) {
  // 2 × 4 and 8 × 1 grids, with and without the positive off-diagonal mass term
  for (unsigned seed = 1; seed <= 6; ++seed)
    for (bool mass : {false, true}) {
      const BoundQP qp = seed % 2 ? random_problem(4, 2, seed, mass) : random_problem(8, 1, seed, mass);
      const VectorXd exact = brute_force(qp);
      for (const std::string& name : cdyn::step_solver_names()) {
        auto solver = cdyn::make_step_solver(name, QPOptions{});
        const QPResult res = solver->solve(qp);
        expect_kkt(qp, res, 1e-10, name);
        const ErrorBound bound(qp);
        EXPECT_LE((res.X - exact).lpNorm<Eigen::Infinity>(), std::max(bound(qp, res), 1e-14))
            << name << " seed " << seed << " mass " << mass;
      }
    }
}

TEST(QPSolvers, RandomGridProblemsAllSolversAgree) {
  struct Case {
    int kx, ky;
    unsigned seed;
    bool mass;
  };
  const Case cases[] = {{50, 1, 11, false}, {10, 10, 12, false}, {12, 12, 13, true}, {24, 24, 14, false}};
  const double tol = 1e-10;
  for (const Case& c : cases) {
    const BoundQP qp = random_problem(c.kx, c.ky, c.seed, c.mass);
    const ErrorBound bound(qp);
    std::vector<QPResult> results;
    std::vector<double> bounds;
    for (const std::string& name : cdyn::step_solver_names()) {
      QPOptions opt;
      opt.tol = tol;
      opt.pgs_omega = 1.5;
      auto solver = cdyn::make_step_solver(name, opt);
      results.push_back(solver->solve(qp));
      expect_kkt(qp, results.back(), tol, name);
      bounds.push_back(bound(qp, results.back()));
      std::cout << "[ grid " << c.kx << "x" << c.ky << (c.mass ? " +mass" : "") << " ] " << name
                << ": iterations " << results.back().iterations << ", kkt " << results.back().kkt_residual
                << ", error bound " << bounds.back() << ", active " << results.back().active.size() << "\n";
    }
    for (std::size_t a = 0; a < results.size(); ++a)
      for (std::size_t b = a + 1; b < results.size(); ++b) {
        const double diff = (results[a].X - results[b].X).lpNorm<Eigen::Infinity>();
        EXPECT_LE(diff, bounds[a] + bounds[b]) << cdyn::step_solver_names()[a] << " vs " << cdyn::step_solver_names()[b];
        std::cout << "    |X_" << cdyn::step_solver_names()[a] << " - X_" << cdyn::step_solver_names()[b]
                  << "|_inf = " << diff << " (bound " << bounds[a] + bounds[b] << ")\n";
      }
  }
}

TEST(QPSolvers, PdasWarmStartFromTheSolutionTakesOneIteration) {
  const BoundQP qp = random_problem(20, 20, 21, true);
  cdyn::PDASSolver pdas;
  const QPResult cold = pdas.solve(qp);
  EXPECT_GT(cold.iterations, 1);
  const QPResult warm = pdas.solve(qp, &cold);
  EXPECT_EQ(warm.iterations, 1);
  EXPECT_TRUE(warm.converged);
  EXPECT_EQ(warm.active, cold.active);
  EXPECT_LE((warm.X - cold.X).lpNorm<Eigen::Infinity>(), 1e-13);
  // a fresh solver object warm-started from it: also one iteration
  cdyn::PDASSolver other;
  EXPECT_EQ(other.solve(qp, &cold).iterations, 1);
}

TEST(QPSolvers, PdasRowUpdatesGiveTheSameAnswerAsRefactorization) {
  // A sequence of right-hand sides, as in a time loop: S fixed, the active set moves.
  BoundQP qp = random_problem(30, 30, 31, false);
  // (CG off: this compares the two ways to change the factor itself.)
  QPOptions refactor_only;
  refactor_only.pdas_update_limit = 0;
  refactor_only.pdas_cg_iterations = 0;
  QPOptions updates = refactor_only;
  updates.pdas_update_limit = 1000000;
  cdyn::PDASSolver a(refactor_only), b(updates);
  QPResult ra, rb;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(-0.05, 0.05);
  for (int step = 0; step < 8; ++step) {
    for (int i = 0; i < qp.size(); ++i) qp.r[i] += U(gen);
    ra = a.solve(qp, step ? &ra : nullptr);
    rb = b.solve(qp, step ? &rb : nullptr);
    EXPECT_LE((ra.X - rb.X).lpNorm<Eigen::Infinity>(), 1e-12 * std::max(1.0, ra.X.lpNorm<Eigen::Infinity>()));
    EXPECT_EQ(ra.active, rb.active);
    EXPECT_LE(rb.kkt_residual, 1e-10);
  }
  EXPECT_EQ(a.counters().row_updates, 0);
  EXPECT_GT(b.counters().row_updates, 0);
  EXPECT_LT(b.counters().factorizations, a.counters().factorizations);
  std::cout << "refactor only: " << a.counters().factorizations << " factorizations; with row updates: "
            << b.counters().factorizations << " factorizations + " << b.counters().row_updates << " row updates\n";
}

// Resting contact on a k × k grid: a body on the obstacle u ≥ 0 pushed onto it
// everywhere except in a patch of radius r0 + dr·step cells that grows step by step
// (lift-off), so that most unknowns are held.  Six steps solved by `whole` (the factor of
// S̃ in S's pattern) and by `block` (QPOptions::pdas_free_block), CG off: two
// factorizations of the same reduced system, so the same active sets and the same
// solution to round-off (asserted 1e-12 relative: both are direct solves of a system
// whose condition here is O(10)).  Returns block's analyses after the first step.
int lift_off(int k, double r0, double dr, cdyn::PDASSolver& whole, cdyn::PDASSolver& block) {
  const int n = k * k;
  std::mt19937 gen(17);
  BoundQP qp;
  qp.S = grid_matrix(k, k, gen, true);
  qp.lower = VectorXd::Zero(n);
  qp.upper = VectorXd::Constant(n, inf);
  QPResult ra, rb;
  int analyses_after_first = 0;
  for (int step = 0; step < 6; ++step) {
    const double radius = r0 + dr * step;
    qp.r = VectorXd::Constant(n, -1.0);
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i)
        if (std::hypot(i - k / 2.0, j - k / 2.0) < radius) qp.r[j * k + i] = 5.0;
    ra = whole.solve(qp, step ? &ra : nullptr);
    rb = block.solve(qp, step ? &rb : nullptr);
    if (step == 0) analyses_after_first = block.counters().analyses;
    EXPECT_GT(static_cast<int>(rb.active.size()), n / 2);
    EXPECT_EQ(ra.active, rb.active);
    EXPECT_LE((ra.X - rb.X).lpNorm<Eigen::Infinity>(), 1e-12 * ra.X.lpNorm<Eigen::Infinity>());
    EXPECT_LE(rb.kkt_residual, 1e-10);
  }
  return analyses_after_first;
}

// The options of lift_off's two solvers: the free block always (1) or never (0), no CG.
QPOptions free_block_options(double fraction) {
  QPOptions o;
  o.pdas_free_block = fraction;
  o.pdas_cg_iterations = 0;
  return o;
}

TEST(QPSolvers, PdasFreeBlockFactorGivesTheAnswerOfTheWholeFactor) {
  cdyn::PDASSolver a(free_block_options(0.0)), b(free_block_options(1.0));
  lift_off(40, 3.0, 2.0, a, b);
  // the free block was factorized (and analysed for each new free set)
  EXPECT_GT(b.counters().analyses, a.counters().analyses);
}

TEST(QPSolvers, PdasFreeBlockFollowsAFewSwitchingUnknownsByRowUpdates) {
  // The patch growing by a tenth of a cell a step: each new set frees a few unknowns
  // (8–20) next to the free ones, within the block's margin (the held neighbours of I),
  // so the block factor follows them by row updates — no new analysis after the first
  // block (without the margin, one per step) — and gives the whole factor's answer.
  cdyn::PDASSolver a(free_block_options(0.0)), b(free_block_options(1.0));
  const int analyses_after_first = lift_off(60, 10.0, 0.1, a, b);
  EXPECT_GT(b.counters().row_updates, 0);
  EXPECT_EQ(b.counters().analyses, analyses_after_first);
}

// The CG path's set-up: a solver that takes CG for every new set (pdas_cg_always: at
// 400 unknowns the flop counts of cg_pays would choose a refactorization), and its
// factor that of S with no active bound (a first call without bounds).
QPOptions cg_always() {
  QPOptions o;
  o.pdas_cg_always = true;
  return o;
}
void factorize_without_bounds(cdyn::PDASSolver& pdas, const BoundQP& qp) {
  BoundQP unbounded = qp;
  unbounded.lower.setConstant(-std::numeric_limits<double>::infinity());
  unbounded.upper.setConstant(std::numeric_limits<double>::infinity());
  pdas.solve(unbounded);
}

TEST(QPSolvers, PdasSolvesANewActiveSetByCgUntilItSettles) {
  // A solver whose factor is that of S with no active bound (its first call had no
  // bounds), then the bounded QP solved again and again from its own solution, as in a
  // time loop whose contact zone has stopped moving.  Each of these calls meets an
  // active set that differs from the factor's: the first two solve it by CG
  // (pdas_cg_always: at 400 unknowns the flop counts of cg_pays would choose a
  // refactorization), then the set has served three solves in a row and the factor is
  // brought to it; from there on a call is one forward/back solve with the factor and
  // no CG.
  const BoundQP qp = random_problem(20, 20, 7, false);
  const QPResult solution = cdyn::PDASSolver().solve(qp);
  ASSERT_GT(std::count_if(solution.active.begin(), solution.active.end(), [](auto a) { return a != 0; }), 0);
  cdyn::PDASSolver pdas(cg_always());
  factorize_without_bounds(pdas, qp);
  const auto c0 = pdas.counters();
  std::vector<int> cg_solves, factor_changes;
  for (int call = 0; call < 4; ++call) {
    const QPResult r = pdas.solve(qp, &solution);
    EXPECT_EQ(r.iterations, 1);
    EXPECT_LE((r.X - solution.X).lpNorm<Eigen::Infinity>(), 1e-10);
    cg_solves.push_back(pdas.counters().cg_solves - c0.cg_solves);
    factor_changes.push_back(pdas.counters().factorizations + pdas.counters().row_updates - c0.factorizations -
                             c0.row_updates);
  }
  EXPECT_EQ(cg_solves, (std::vector<int>{1, 2, 2, 2}));  // CG twice, then the factor
  EXPECT_EQ(factor_changes[1], 0);
  EXPECT_GT(factor_changes[2], 0);                      // the factor caught up on the third call
  EXPECT_EQ(factor_changes[3], factor_changes[2]);      // and stays
}

TEST(QPSolvers, PdasCountsTheSolvesOfOneStepAsOneAndSolvesThemToRoundOffWhenAsked) {
  // As above, but each step solves its QP twice (a second right-hand side, as the
  // discrete gradient's energy correction does): the set has then served five solves
  // by the third step, yet only three steps, so the factor catches up at the third
  // step as above, not at the second.  A repeat asked to round-off is solved by the
  // factor brought to its set: to the direct solve's accuracy, where CG stops at tol.
  const BoundQP qp = random_problem(20, 20, 7, false);
  const QPResult solution = cdyn::PDASSolver().solve(qp);
  BoundQP again = qp;
  again.r *= 1.0 + 1e-9;  // the same active set, another right-hand side
  const QPResult again_solution = cdyn::PDASSolver().solve(again);
  ASSERT_EQ(again_solution.active, solution.active);
  cdyn::PDASSolver pdas(cg_always());
  factorize_without_bounds(pdas, qp);
  const auto c0 = pdas.counters();
  auto factor_changes = [&] {
    return pdas.counters().factorizations + pdas.counters().row_updates - c0.factorizations - c0.row_updates;
  };
  std::vector<int> changes;
  for (int step = 0; step < 3; ++step) {
    const QPResult r = pdas.solve(qp, &solution);
    pdas.next_in_same_step(false);
    const QPResult r2 = pdas.solve(again, &r);
    EXPECT_LE((r2.X - again_solution.X).lpNorm<Eigen::Infinity>(), 1e-10);
    changes.push_back(factor_changes());
  }
  EXPECT_EQ(changes[0], 0);
  EXPECT_EQ(changes[1], 0);  // five solves, two steps: not settled
  EXPECT_GT(changes[2], 0);  // the third step's first solve brought the factor to the set

  // A fresh solver on CG, its repeat asked to round-off: the factor, not CG.
  cdyn::PDASSolver fresh(cg_always());
  factorize_without_bounds(fresh, qp);
  const auto c1 = fresh.counters();
  const QPResult r = fresh.solve(qp, &solution);
  EXPECT_EQ(fresh.counters().row_updates + fresh.counters().factorizations, c1.row_updates + c1.factorizations);
  fresh.next_in_same_step(true);
  const int cg_before = fresh.counters().cg_solves;
  const QPResult exact = fresh.solve(again, &r);
  EXPECT_EQ(fresh.counters().cg_solves, cg_before);
  EXPECT_GT(fresh.counters().row_updates + fresh.counters().factorizations, c1.row_updates + c1.factorizations);
  EXPECT_LE((exact.X - again_solution.X).lpNorm<Eigen::Infinity>(), 1e-13 * again_solution.X.lpNorm<Eigen::Infinity>());
}

TEST(QPSolvers, PdasOnLooseCgIteratesEndsAtTheToleranceAndTheDirectSolution) {
  // A cold start whose every system is solved by CG (the factor is that of S with no
  // active bound): the iterates are solved loosely (reduced_system.cpp kLooseSolve) and the
  // repeating active set is confirmed on a tight solve.  The result must meet tol like
  // any other, with the active set of the direct solver (factor only) and X within the
  // sum of the two a-posteriori error bounds.  (pdas_cg_always: at 400 unknowns the flop
  // counts would choose a refactorization.)
  const BoundQP qp = random_problem(20, 20, 7, false);
  QPOptions direct_options;
  direct_options.pdas_cg_iterations = 0;
  const QPResult direct = cdyn::PDASSolver(direct_options).solve(qp);
  cdyn::PDASSolver pdas(cg_always());
  factorize_without_bounds(pdas, qp);
  const auto c0 = pdas.counters();
  const QPResult r = pdas.solve(qp);
  const int cg_solves = pdas.counters().cg_solves - c0.cg_solves;
  // The first system (no active bound) is the factor's own; every other one is by CG:
  // at least one loose iterate, the loose repeat of its set and the tight confirm.
  EXPECT_EQ(cg_solves, r.iterations - 1);
  EXPECT_GE(cg_solves, 3);
  expect_kkt(qp, r, QPOptions{}.tol, "pdas on CG iterates");
  EXPECT_EQ(r.active, direct.active);
  const ErrorBound bound(qp);
  EXPECT_LE((r.X - direct.X).lpNorm<Eigen::Infinity>(), bound(qp, r) + bound(qp, direct));
}

TEST(QPSolvers, PdasBringsTheFactorToANewSetWhereThatCostsLessThanCg) {
  // A chain of 400 unknowns (tridiagonal S): its factorization costs a few thousand
  // flops, less than one CG iteration (2 nnz(S) + 12 n ≈ 7e3).  The first new active
  // set goes to CG, which measures CG's cost (cg_pays in explicit_reduced_system.cpp);
  // the next ones are brought to the factor (row updates), not solved by CG again,
  // although no row update had been measured before — CG until then was the rule that
  // made the thin beam's switching steps 5–20 times its other steps (docs/performance.md).
  const int n = 400;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.5);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  BoundQP qp;
  qp.S.resize(n, n);
  qp.S.setFromTriplets(t.begin(), t.end());
  qp.S.makeCompressed();
  qp.lower = VectorXd::Constant(n, -inf);
  qp.upper = VectorXd::Constant(n, inf);
  qp.r = VectorXd::Constant(n, 1.0);
  cdyn::PDASSolver pdas;
  QPResult r = pdas.solve(qp);  // no bound: the factor of S
  qp.lower.setZero();
  auto push_down = [&](int from, int to) {  // X < 0 there without the bound
    qp.r.setConstant(1.0);
    qp.r.segment(from, to - from).setConstant(-1.0);
  };
  push_down(100, 200);
  r = pdas.solve(qp, &r);  // PDAS meets several sets on its way: the first by CG only
  expect_kkt(qp, r, QPOptions{}.tol, "first set");
  EXPECT_EQ(pdas.counters().cg_solves, 1);
  const int updates = pdas.counters().row_updates;
  EXPECT_GT(updates, 0);
  push_down(150, 260);
  r = pdas.solve(qp, &r);
  expect_kkt(qp, r, QPOptions{}.tol, "second set");
  EXPECT_EQ(pdas.counters().cg_solves, 1);  // not CG again
  EXPECT_GT(pdas.counters().row_updates, updates);
}

// The obstacle X ≥ 0 on grid_laplacian(m, diagonal), no load yet.
BoundQP grid_obstacle(int m, double diagonal) {
  BoundQP qp;
  qp.S = grid_laplacian(m, diagonal);
  qp.lower = VectorXd::Zero(m * m);
  qp.upper = VectorXd::Constant(m * m, inf);
  return qp;
}

TEST(QPSolvers, PdasLeavesTheFactorWhereAChatteringSetWouldNotRepayASync) {
  // A well-conditioned 2D step matrix (the 5-point Laplacian plus 20 I on a 30 × 30
  // grid: CG converges in a few iterations, a refactorization costs tens of them) and a
  // contact zone that chatters: two active sets in turn, each for three calls — long
  // enough to count as settled (resync_due), too short to repay bringing the factor
  // there (resync_pays).  The first settled set is synced (nothing seen yet says it will
  // not stay); once settled sets have been seen to serve one call after settling, the
  // factor is left alone: no factorization and no row update in the later cycles, each
  // call by CG.  (With a resync at every settled set — the rule before — each cycle
  // changes the factor: a chattering membrane spent 3.7 ms a step on it.)
  const int m = 30, n = m * m;
  BoundQP qp = grid_obstacle(m, 24.0);
  auto press = [&](int first_row, int last_row) {  // X < 0 on those rows without the bound
    qp.r.setConstant(n, 1.0);
    qp.r.segment(first_row * m, (last_row - first_row) * m).setConstant(-1.0);
  };
  cdyn::PDASSolver pdas;
  press(5, 15);
  QPResult r = pdas.solve(qp);
  auto syncs = [&] { return pdas.counters().factorizations + pdas.counters().row_updates; };
  int after_two_cycles = 0;
  for (int cycle = 0; cycle < 6; ++cycle) {
    if (cycle == 2) after_two_cycles = syncs();
    press(cycle % 2 ? 5 : 12, cycle % 2 ? 15 : 22);
    for (int call = 0; call < 3; ++call) {
      r = pdas.solve(qp, &r);
      expect_kkt(qp, r, QPOptions{}.tol, "cycle " + std::to_string(cycle));
    }
  }
  EXPECT_GT(after_two_cycles, 1);  // the first factorization and the first settled set's sync
  EXPECT_EQ(syncs(), after_two_cycles);
  EXPECT_GT(pdas.counters().cg_solves, 12);
}

TEST(QPSolvers, PdasGoesBackToTheFactorOfSWhenNothingIsHeld) {
  // The body lifts off: after calls with a held zone, brought into the factor, the load
  // turns and nothing is held.  The step is then the unconstrained one, S X = r, and S's
  // own factor (made by the first call, kept aside when the factor left it) solves it:
  // no factorization, no row update, no CG — one solve, and the answer of a fresh
  // solver's factor of S to round-off.  (Before, the chattering membrane at n = 160,
  // P1/P1 backward Euler, ran 80 steps with nothing held at 2 PDAS iterations of CG
  // each: 4.6–5.0 ms a step against the linear run's 2.1–2.6.)
  const int m = 30, n = m * m;
  BoundQP qp = grid_obstacle(m, 24.0);
  qp.r.setConstant(n, 1.0);
  cdyn::PDASSolver pdas;
  QPResult r = pdas.solve(qp);  // nothing held: the factor of S
  qp.r.segment(5 * m, 10 * m).setConstant(-1.0);
  for (int call = 0; call < 4; ++call) r = pdas.solve(qp, &r);
  ASSERT_GT(r.active.size(), 0u);
  const auto before = pdas.counters();
  ASSERT_GT(before.factorizations + before.row_updates, 1);  // the factor left S's
  qp.r.setConstant(n, 1.0);  // lift-off
  r = pdas.solve(qp, &r);
  expect_kkt(qp, r, QPOptions{}.tol, "lift-off");
  EXPECT_TRUE(r.active.empty());
  const auto after = pdas.counters();
  EXPECT_EQ(after.factorizations, before.factorizations);
  EXPECT_EQ(after.row_updates, before.row_updates);
  EXPECT_EQ(after.cg_solves, before.cg_solves);
  // (the first iterate holds the last call's set, by the factor as it is; the second none)
  EXPECT_EQ(after.solves, before.solves + 2);
  r = pdas.solve(qp, &r);  // and the next call with nothing held is one solve
  EXPECT_EQ(pdas.counters().solves, after.solves + 1);
  EXPECT_EQ(pdas.counters().factorizations + pdas.counters().row_updates, after.factorizations + after.row_updates);
  cdyn::PDASSolver fresh;
  const QPResult reference = fresh.solve(qp);
  EXPECT_LT((r.X - reference.X).lpNorm<Eigen::Infinity>(), 1e-14 * reference.X.lpNorm<Eigen::Infinity>());
}

TEST(QPSolvers, PdasHoldsAFewUnknownsByTheFactorOfSAndTheirCapacitanceMatrix) {
  // A membrane touching the obstacle at a few points that move from call to call (the
  // chattering contact's sets of 2–20 vertices).  With S's own factor in hand, each set
  // is solved by it and the capacitance matrix of the held unknowns: no CG, no
  // factorization, no row update after the first call, and every answer the factor of
  // S̃'s own to round-off.  Without it (pdas_capacitance_from = ∞), the same calls go to
  // CG (before: the chattering membrane at n = 160, P1+/P0 midpoint, spent two CG
  // solves, 4–5 ms, on each QP that a solve with the factor, 1.8 ms, now serves).  (On
  // this small grid only when asked: by default a solve must cost 10⁶ flops.)
  const int m = 30, n = m * m;
  BoundQP qp = grid_obstacle(m, 24.0);
  QPOptions with, by_factor, without;
  with.pdas_capacitance_from = 0.0;
  by_factor.pdas_cg_iterations = 0;
  by_factor.pdas_capacitance_from = without.pdas_capacitance_from = inf;
  cdyn::PDASSolver pdas(with), cg(without), by_default;
  qp.r.setConstant(n, 1.0);
  QPResult r = pdas.solve(qp), r_cg = cg.solve(qp), r_default = by_default.solve(qp);
  const auto first = pdas.counters();
  for (int call = 0; call < 6; ++call) {
    qp.r.setConstant(n, 1.0);
    for (int spot = 0; spot < 3; ++spot) qp.r[(7 * call + 97 * spot + 31) % n] = -5.0;  // pressed: held
    r = pdas.solve(qp, &r);
    r_cg = cg.solve(qp, &r_cg);
    r_default = by_default.solve(qp, &r_default);
    expect_kkt(qp, r, QPOptions{}.tol, "call " + std::to_string(call));
    ASSERT_EQ(r.active.size(), 3u);
    cdyn::PDASSolver fresh(by_factor);
    const QPResult expected = fresh.solve(qp);
    EXPECT_LT((r.X - expected.X).lpNorm<Eigen::Infinity>(), 1e-14 * expected.X.lpNorm<Eigen::Infinity>());
  }
  const auto after = pdas.counters();
  EXPECT_GT(after.capacitance_solves, 6);
  EXPECT_EQ(after.cg_solves, 0);
  EXPECT_EQ(after.factorizations, first.factorizations);
  EXPECT_EQ(after.row_updates, 0);
  EXPECT_EQ(after.capacitance_columns, 18);  // each held unknown's column made once
  EXPECT_GT(cg.counters().cg_solves, 6);
  EXPECT_EQ(cg.counters().capacitance_solves, 0);
  EXPECT_EQ(by_default.counters().capacitance_solves, 0);  // (a solve here: 5e4 flops)
}

TEST(QPSolvers, PdasHoldsASetWhoseColumnsCostMoreThanASolveByCapacitanceOnceCGIsPriced) {
  // Once CG's pair of solves has been measured, a set of held unknowns whose new columns
  // and capacitance matrix cost more than one solve, but less than twice what the CG pair
  // costs beyond it, is held by S's factor and its capacitance matrix instead of the pair
  // (the chattering membrane's sets of 12–50 vertices).  A strip pressed onto the
  // obstacle goes to CG (its capacitance matrix would cost hundreds of solves); after a
  // lift-off, 20 scattered unknowns pressed at once make 20 new columns and their
  // matrix: more than a solve's flops (with that budget, the rule before, this set went
  // to CG; 15 did not), less than twice the pair's beyond it (25 do not).  They go to the
  // capacitance solve, and the answer is S̃'s own factor's to round-off.
  const int m = 30, n = m * m;
  BoundQP qp = grid_obstacle(m, 24.0);
  QPOptions options, by_factor;
  options.pdas_capacitance_from = 0.0;
  by_factor.pdas_cg_iterations = 0;
  by_factor.pdas_capacitance_from = inf;
  cdyn::PDASSolver pdas(options);
  qp.r.setConstant(n, 1.0);
  QPResult r = pdas.solve(qp);  // nothing held: the factor of S
  qp.r.segment(5 * m, 10 * m).setConstant(-1.0);
  r = pdas.solve(qp, &r);  // the strip
  ASSERT_EQ(r.active.size(), static_cast<std::size_t>(10 * m));
  ASSERT_GT(pdas.counters().cg_solves, 0);
  qp.r.setConstant(n, 1.0);
  r = pdas.solve(qp, &r);  // lift-off: S's own factor again
  ASSERT_TRUE(r.active.empty());
  const auto before = pdas.counters();
  for (int spot = 0; spot < 20; ++spot) qp.r[(37 * spot + 11) % n] = -5.0;
  r = pdas.solve(qp, &r);
  expect_kkt(qp, r, QPOptions{}.tol, "20 pressed");
  ASSERT_EQ(r.active.size(), 20u);
  const auto after = pdas.counters();
  EXPECT_EQ(after.cg_solves, before.cg_solves);
  EXPECT_GT(after.capacitance_solves, before.capacitance_solves);
  EXPECT_EQ(after.factorizations + after.row_updates, before.factorizations + before.row_updates);
  cdyn::PDASSolver fresh(by_factor);
  const QPResult expected = fresh.solve(qp);
  EXPECT_LT((r.X - expected.X).lpNorm<Eigen::Infinity>(), 1e-14 * expected.X.lpNorm<Eigen::Infinity>());
}

TEST(QPSolvers, PdasPricesALiftOffFromAFreeBlockAsTheWholeFactorization) {
  // A body resting on the obstacle (its factor a free block's: most unknowns held) lifts
  // off but for a strip.  Bringing the factor to that set is a factorization of the
  // whole S̃, which costs more than CG here (100 × 100 grid): the set goes to CG.  Priced
  // as the free block's own factorization (a patch of 100 unknowns), it was synced: the
  // chattering membrane made two factorizations of S̃ at its lift-off (n = 160, P1+/P0
  // midpoint: 16.7, 16.2 ms a step over 100 steps with them, 14.8, 14.5 without).
  const int m = 100, n = m * m;
  BoundQP qp = grid_obstacle(m, 8.0);
  qp.r = VectorXd::Constant(n, 1.0);
  cdyn::PDASSolver pdas;
  QPResult r = pdas.solve(qp);  // nothing held: S's factor
  qp.r.setConstant(-1.0);       // resting: pressed everywhere but a 10 × 10 patch
  for (int i = 40; i < 50; ++i) qp.r.segment(i * m + 40, 10).setConstant(1.0);
  for (int call = 0; call < 2; ++call) r = pdas.solve(qp, &r);
  ASSERT_GT(r.active.size(), static_cast<std::size_t>(n / 2));
  qp.r.setConstant(1.0);  // lift-off but for a strip of two grid lines
  qp.r.segment(10 * m, 2 * m).setConstant(-1.0);
  const auto before = pdas.counters();
  r = pdas.solve(qp, &r);
  expect_kkt(qp, r, QPOptions{}.tol, "lift-off");
  ASSERT_GT(r.active.size(), 0u);
  ASSERT_LT(r.active.size(), static_cast<std::size_t>(n / 10));
  EXPECT_EQ(pdas.counters().factorizations, before.factorizations);
  EXPECT_GT(pdas.counters().cg_solves, before.cg_solves);
}

TEST(QPSolvers, PdasPricesANewSetWithFewFreeUnknownsAsAFreeBlockFactorization) {
  // Resting contact: most unknowns held, the free ones in a patch that moves.  The factor
  // is S's (the first call has no bounds); S's whole factorization on this 60 × 60 grid
  // costs more than a CG solve, but the factorization of the free block S_II — about 3 %
  // of the unknowns — far less.  The first new set goes to CG (measuring its cost); the
  // next must be priced as what sync_factor would do, a free-block factorization, and
  // taken that way (priced as S's whole factorization, every such set went to CG: the
  // resting membrane's reconstruction at n = 640, 40 % of its step time).
  const int m = 60, n = m * m;
  BoundQP qp;
  qp.S = grid_laplacian(m, 8.0);
  qp.upper = VectorXd::Constant(n, inf);
  qp.lower = VectorXd::Constant(n, -inf);
  qp.r = VectorXd::Constant(n, 1.0);
  cdyn::PDASSolver pdas;
  QPResult r = pdas.solve(qp);  // no bound: the factor of S
  qp.lower.setZero();
  auto lift = [&](int first) {  // pressed onto X ≥ 0 everywhere but a 10 × 10 patch
    qp.r.setConstant(-1.0);
    for (int i = first; i < first + 10; ++i) qp.r.segment(i * m + first, 10).setConstant(1.0);
  };
  lift(20);
  r = pdas.solve(qp, &r);
  expect_kkt(qp, r, QPOptions{}.tol, "first patch");
  EXPECT_GT(static_cast<int>(r.active.size()), n * 9 / 10);
  // PDAS met two sets on its way: the first by CG, the second by a free block's factor
  // (an analysis of its own besides S's)
  EXPECT_EQ(pdas.counters().cg_solves, 1);
  EXPECT_EQ(pdas.counters().analyses, 2);
  const int factorizations = pdas.counters().factorizations;
  lift(22);
  r = pdas.solve(qp, &r);
  expect_kkt(qp, r, QPOptions{}.tol, "moved patch");
  EXPECT_EQ(pdas.counters().cg_solves, 1);  // not CG again: the new free block factorized
  EXPECT_GT(pdas.counters().factorizations, factorizations);
}

TEST(QPSolvers, PdasReusesItsFactorizationAcrossCalls) {
  const BoundQP qp = random_problem(15, 15, 41, false);
  cdyn::PDASSolver pdas;
  const QPResult first = pdas.solve(qp);
  const auto after_first = pdas.counters();
  EXPECT_EQ(after_first.analyses, 1);
  // same S, same active set: no new analysis, no new factorization, one solve
  const QPResult again = pdas.solve(qp, &first);
  EXPECT_EQ(pdas.counters().analyses, 1);
  EXPECT_EQ(pdas.counters().factorizations, after_first.factorizations);
  EXPECT_EQ(pdas.counters().solves, after_first.solves + 1);
  EXPECT_EQ(again.iterations, 1);
  // new values, same pattern: no new analysis
  BoundQP scaled = qp;
  scaled.S *= 2.0;
  pdas.solve(scaled);
  EXPECT_EQ(pdas.counters().analyses, 1);
}

// BoundQP::matrices_id: matrices named as the last call's are taken as they were, unread;
// matrices renamed or unnamed are compared with the last call's (new when they differ).
TEST(QPChecks, MatricesNamedAsTheLastCallsAreTakenAsUnchanged) {
  BoundQP qp = random_problem(6, 6, 43, false);
  qp.matrices_id = cdyn::new_matrices_id();
  cdyn::CheckedMatrices checked;
  EXPECT_TRUE(checked.check(qp, true, "test"));
  EXPECT_FALSE(checked.check(qp, true, "test"));
  qp.S *= 2.0;  // in place, under the same name: the owner broke the contract, unseen
  EXPECT_FALSE(checked.check(qp, true, "test"));
  qp.matrices_id = cdyn::new_matrices_id();  // renamed: read, and new
  EXPECT_TRUE(checked.check(qp, true, "test"));
  qp.matrices_id = cdyn::new_matrices_id();  // renamed, the same values: read, not new
  EXPECT_FALSE(checked.check(qp, true, "test"));
  qp.matrices_id = 0;  // unnamed: read at every call
  EXPECT_FALSE(checked.check(qp, true, "test"));
  qp.S *= 0.5;
  EXPECT_TRUE(checked.check(qp, true, "test"));
  // matrices that fail the checks are not named: the next call reads them again
  BoundQP bad = qp;
  bad.matrices_id = cdyn::new_matrices_id();
  bad.S.coeffRef(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(checked.check(bad, true, "test"), cdyn::InputError);
  EXPECT_THROW(checked.check(bad, true, "test"), cdyn::InputError);
}

// A step solver given renamed matrices solves with them: PDAS factorizes again.
TEST(QPSolvers, PdasSolvesRenamedMatricesWithANewFactor) {
  BoundQP qp = random_problem(12, 12, 43, false);
  qp.matrices_id = cdyn::new_matrices_id();
  cdyn::PDASSolver pdas;
  const QPResult first = pdas.solve(qp);
  const int factorizations = pdas.counters().factorizations;
  pdas.solve(qp, &first);
  EXPECT_EQ(pdas.counters().factorizations, factorizations);
  qp.S *= 2.0;
  qp.matrices_id = cdyn::new_matrices_id();
  const QPResult renamed = pdas.solve(qp, &first);
  EXPECT_GT(pdas.counters().factorizations, factorizations);
  expect_kkt(qp, renamed, 1e-10, "pdas, renamed");
}

// ----- saddle form -----------------------------------------------------------------------

// A small saddle form: A = 1D Laplacian (n), B random sparse (m × n), C SPD tridiagonal;
// the explicit S = A + c Bᵀ C⁻¹ B computed densely as the reference problem.
struct SaddleCase {
  BoundQP saddle_qp, explicit_qp;
};
SaddleCase saddle_case(int n, int m, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  SaddleCase sc;
  std::vector<Eigen::Triplet<double>> ta, tb, tc;
  for (int i = 0; i < n; ++i) {
    ta.emplace_back(i, i, 2.0);
    if (i > 0) ta.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) ta.emplace_back(i, i + 1, -1.0);
  }
  for (int k = 0; k < m; ++k) {
    tc.emplace_back(k, k, 4.0 / 6.0);
    if (k > 0) tc.emplace_back(k, k - 1, 1.0 / 6.0);
    if (k + 1 < m) tc.emplace_back(k, k + 1, 1.0 / 6.0);
    for (int j = 0; j < n; ++j)
      if (std::abs(j * m - k * n) < 2 * n) tb.emplace_back(k, j, 0.5 + 0.25 * U(gen));
  }
  cdyn::SaddleForm f;
  f.A.resize(n, n);
  f.A.setFromTriplets(ta.begin(), ta.end());
  f.B.resize(m, n);
  f.B.setFromTriplets(tb.begin(), tb.end());
  f.C.resize(m, m);
  f.C.setFromTriplets(tc.begin(), tc.end());
  f.c = 3.0;
  const MatrixXd Sd = MatrixXd(f.A) + f.c * MatrixXd(f.B).transpose() * MatrixXd(f.C).inverse() * MatrixXd(f.B);
  sc.explicit_qp.S = Sd.sparseView(0.0, 0.0);
  sc.explicit_qp.S.makeCompressed();
  sc.saddle_qp.saddle = f;
  VectorXd r(n), lower(n), upper(n);
  for (int i = 0; i < n; ++i) {
    r[i] = 2.0 * U(gen);
    lower[i] = i % 2 ? -0.05 + 0.05 * U(gen) : -inf;
    upper[i] = i % 3 == 0 ? 0.1 + 0.05 * U(gen) : inf;
  }
  sc.saddle_qp.r = sc.explicit_qp.r = r;
  sc.saddle_qp.lower = sc.explicit_qp.lower = lower;
  sc.saddle_qp.upper = sc.explicit_qp.upper = upper;
  return sc;
}

TEST(QPSolvers, SaddleFormGivesTheSameSolutionAsTheExplicitS) {
  const SaddleCase sc = saddle_case(40, 25, 51);
  // the reference: pdas on the dense-computed explicit S
  auto reference_solver = cdyn::make_step_solver("pdas", QPOptions{});
  const QPResult ref = reference_solver->solve(sc.explicit_qp);
  ASSERT_GT(ref.active.size(), 3u);
  const ErrorBound bound(sc.explicit_qp);
  for (const std::string& name : {std::string("pdas"), std::string("ipopt"), std::string("nlopt")}) {
    auto solver = cdyn::make_step_solver(name, QPOptions{});
    const QPResult res = solver->solve(sc.saddle_qp);
    expect_kkt(sc.saddle_qp, res, 1e-10, name + " (saddle)");
    // the same measure on the explicit problem agrees
    EXPECT_LE(cdyn::kkt_residual(sc.explicit_qp, res.X), 1e-9) << name;
    const double diff = (res.X - ref.X).lpNorm<Eigen::Infinity>();
    QPResult as_explicit = res;
    as_explicit.reaction = sc.explicit_qp.S * res.X - sc.explicit_qp.r;
    EXPECT_LE(diff, bound(sc.explicit_qp, ref) + bound(sc.explicit_qp, as_explicit)) << name;
    EXPECT_EQ(res.active, ref.active) << name;
    std::cout << "saddle " << name << ": |X - X_explicit|_inf = " << diff << ", iterations " << res.iterations
              << "\n";
  }
  // warm start in saddle form: one iteration
  cdyn::PDASSolver pdas;
  const QPResult cold = pdas.solve(sc.saddle_qp);
  EXPECT_EQ(pdas.solve(sc.saddle_qp, &cold).iterations, 1);
}

TEST(QPSolvers, PgsRefusesTheSaddleForm) {
  const SaddleCase sc = saddle_case(10, 6, 3);
  auto pgs = cdyn::make_step_solver("pgs", QPOptions{});
  try {
    pgs->solve(sc.saddle_qp);
    FAIL() << "pgs accepted the saddle form";
  } catch (const cdyn::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("saddle"), std::string::npos) << e.what();
  }
}

// ----- the cycling guard -----------------------------------------------------------------

// Plain PDAS (Newton-min) can cycle when S is not an M-matrix.  This 3 × 3 SPD case
// (X ≥ 0) was found by a random search for a cold start that repeats an active set.
// The test first replays plain PDAS densely (the rule of qp/pdas/pdas.hpp, with D = diag S)
// to show that it cycles, then checks that the solver's guard still returns the exact,
// enumerated solution.
TEST(QPSolvers, PdasCyclingGuardStillFindsTheSolution) {
  MatrixXd S(3, 3);
  S << 13.1, 17, -4, 17, 26.1, -10, -4, -10, 8.1;
  BoundQP qp;
  qp.S = S.sparseView();
  qp.S.makeCompressed();
  qp.r = Eigen::Vector3d(0, 4, -4);
  qp.lower = VectorXd::Zero(3);
  qp.upper = VectorXd::Constant(3, inf);
  ASSERT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(S).eigenvalues().minCoeff(), 0.0);

  // plain PDAS, dense: from the unconstrained solution
  std::vector<std::vector<int>> seen;
  VectorXd X = S.ldlt().solve(qp.r), lam = VectorXd::Zero(3);
  bool cycles = false;
  for (int it = 0; it < 20 && !cycles; ++it) {
    std::vector<int> act(3);
    for (int i = 0; i < 3; ++i) act[i] = lam[i] + S(i, i) * (0.0 - X[i]) > 0;
    for (const auto& a : seen) cycles = cycles || (a == act && a != seen.back());
    if (!seen.empty() && act == seen.back()) break;  // converged
    seen.push_back(act);
    MatrixXd St = S;
    VectorXd b = qp.r;
    for (int i = 0; i < 3; ++i)
      if (act[i]) {
        St.row(i).setZero();
        St.col(i).setZero();
        St(i, i) = 1;
        b[i] = 0;
      }
    X = St.ldlt().solve(b);
    lam = S * X - qp.r;
  }
  ASSERT_TRUE(cycles) << "plain PDAS does not cycle on this example any more";

  cdyn::PDASSolver pdas;
  const QPResult res = pdas.solve(qp);
  EXPECT_GT(pdas.counters().damped_iterations, 0);
  expect_kkt(qp, res, 1e-10, "pdas (guarded)");
  const VectorXd exact = brute_force(qp);
  EXPECT_LE((res.X - exact).lpNorm<Eigen::Infinity>(), 1e-14);
  EXPECT_NEAR(exact[1], 4.0 / 26.1, 1e-15);  // only X_1 free: X_1 = r_1 / S_11
  std::cout << "cycling example: " << res.iterations << " iterations, " << pdas.counters().damped_iterations
            << " of them projected Newton\n";
}

// ----- bad input -------------------------------------------------------------------------

template <class E>
void expect_error(const BoundQP& qp, const std::string& solver, const std::string& fragment) {
  auto s = cdyn::make_step_solver(solver, QPOptions{});
  try {
    s->solve(qp);
    ADD_FAILURE() << solver << ": no error, expected one mentioning '" << fragment << "'";
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << solver << ": " << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << solver << ": wrong exception type: " << e.what();
  }
}

TEST(QPSolvers, BadInputIsAClearError) {
  const BoundQP good = random_problem(5, 5, 61, false);
  for (const std::string& name : cdyn::step_solver_names()) {
    BoundQP infeasible = good;
    infeasible.lower[7] = 1.0;
    infeasible.upper[7] = 0.5;
    expect_error<cdyn::InputError>(infeasible, name, "empty");

    BoundQP nan_r = good;
    nan_r.r[3] = std::nan("");
    expect_error<cdyn::InputError>(nan_r, name, "r[3]");

    BoundQP inf_S = good;
    inf_S.S.coeffRef(4, 4) = inf;
    expect_error<cdyn::InputError>(inf_S, name, "not finite");

    BoundQP nan_bound = good;
    nan_bound.lower[2] = std::nan("");
    expect_error<cdyn::InputError>(nan_bound, name, "NaN");

    BoundQP indefinite = good;  // S − 10 I: symmetric, indefinite
    for (int i = 0; i < indefinite.size(); ++i) indefinite.S.coeffRef(i, i) -= 10.0;
    expect_error<cdyn::NumericalError>(indefinite, name, "not positive definite");

    BoundQP unsymmetric = good;
    unsymmetric.S.coeffRef(0, 1) += 0.5;
    expect_error<cdyn::InputError>(unsymmetric, name, "symmetric");

    BoundQP sizes = good;
    sizes.upper.resize(3);
    expect_error<cdyn::InputError>(sizes, name, "entries");
  }
  {  // a solver called again with the matrix it refused refuses it again (its checks are once per S)
    BoundQP indefinite = good;
    for (int i = 0; i < indefinite.size(); ++i) indefinite.S.coeffRef(i, i) = -1.0;
    cdyn::PDASSolver pdas;
    for (int call = 0; call < 2; ++call) EXPECT_THROW(pdas.solve(indefinite), cdyn::NumericalError) << call;
  }
  EXPECT_THROW(cdyn::make_step_solver("simplex", QPOptions{}), cdyn::InputError);
  QPOptions bad_tol;
  bad_tol.tol = -1;
  EXPECT_THROW(cdyn::make_step_solver("pdas", bad_tol), cdyn::InputError);
}

// check_problem's symmetry test (one pass over S, each lower entry matched with its
// mirror) against the dense criterion max |S − Sᵀ| > 1e-10 max |S|: random patterns,
// entries changed or added on one side only, above and below the tolerance.
TEST(QPChecks, SymmetryAsTheDenseCriterion) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> index(0, 29);
  int refused = 0, passed = 0;
  for (int trial = 0; trial < 300; ++trial) {
    MatrixXd dense = MatrixXd::Zero(30, 30);
    for (int k = 0; k < 60; ++k) {
      const int i = index(rng), j = index(rng);
      dense(i, j) = dense(j, i) = u(rng);
    }
    for (int i = 0; i < 30; ++i) dense(i, i) = 10.0;
    const double size = trial % 3 == 0 ? 1e-12 : 1e-6;  // (below and above 1e-10 · 10)
    for (int k = 0; k < trial % 4; ++k) dense(index(rng), index(rng)) += size * (1.0 + u(rng));
    BoundQP qp;
    qp.S = dense.sparseView();
    qp.r = VectorXd::Zero(30);
    qp.lower = VectorXd::Constant(30, -1.0);
    qp.upper = VectorXd::Constant(30, 1.0);
    const bool unsymmetric = (dense - dense.transpose()).cwiseAbs().maxCoeff() > 1e-10 * dense.cwiseAbs().maxCoeff();
    bool threw = false;
    try {
      cdyn::check_problem(qp, true);
    } catch (const cdyn::InputError& e) {
      threw = std::string(e.what()).find("not symmetric") != std::string::npos;
    }
    EXPECT_EQ(threw, unsymmetric) << "trial " << trial;
    (threw ? refused : passed) += 1;
  }
  EXPECT_GT(refused, 50);  // both outcomes met
  EXPECT_GT(passed, 50);
}

TEST(QPSolvers, NonConvergenceIsReportedWithResidualAndIterations) {
  const BoundQP qp = random_problem(20, 20, 71, false);
  QPOptions opt;
  opt.max_iterations = 3;  // pgs: 3 sweeps cannot reach 1e-10
  auto pgs = cdyn::make_step_solver("pgs", opt);
  try {
    pgs->solve(qp);
    FAIL() << "no error";
  } catch (const cdyn::NumericalError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("KKT residual"), std::string::npos) << msg;
    EXPECT_NE(msg.find("after 3 iterations"), std::string::npos) << msg;
  }
  opt.throw_on_failure = false;
  const QPResult res = cdyn::make_step_solver("pgs", opt)->solve(qp);
  EXPECT_FALSE(res.converged);
  EXPECT_GT(res.kkt_residual, 1e-10);
}

}  // namespace

TEST(QPSolvers, PdasCgPathNeverFactorizesAndFindsTheFactorsSolution) {
  // QPOptions::pdas_cg_only: every reduced system by masked CG, no analysis and no
  // factorization, for a cold solve and a warm-started one (a time loop's next step,
  // with r moved).  The same active set as the factor path, and X within the error
  // bounds of the two results (each meets tol = 1e-10 on the natural residual).
  for (bool mass : {false, true}) {
    BoundQP qp = random_problem(30, 30, 23, mass);
    QPOptions cg;
    cg.pdas_cg_only = true;
    cdyn::PDASSolver by_factor, by_cg(cg);
    QPResult rf = by_factor.solve(qp), rc = by_cg.solve(qp);
    for (int step = 0; step < 2; ++step) {
      const ErrorBound bound(qp);
      expect_kkt(qp, rc, 1e-10, "pdas (CG path)");
      EXPECT_EQ(rc.active, rf.active) << "mass " << mass << " step " << step;
      EXPECT_LE((rc.X - rf.X).lpNorm<Eigen::Infinity>(), bound(qp, rf) + bound(qp, rc)) << "mass " << mass;
      qp.r *= 1.1;  // the next "step"
      rf = by_factor.solve(qp, &rf);
      rc = by_cg.solve(qp, &rc);
    }
    EXPECT_EQ(by_cg.counters().factorizations, 0);
    EXPECT_EQ(by_cg.counters().analyses, 0);
    EXPECT_GT(by_cg.counters().cg_solves, 0);
  }
  // the saddle form has no explicit S to run CG on: refused, naming the option
  QPOptions cg;
  cg.pdas_cg_only = true;
  const SaddleCase sc = saddle_case(20, 12, 5);
  try {
    cdyn::PDASSolver(cg).solve(sc.saddle_qp);
    ADD_FAILURE() << "the CG path accepted a saddle-form QP";
  } catch (const cdyn::InputError& e) {
    EXPECT_EQ(e.parameter(), "linear");
  }
}
