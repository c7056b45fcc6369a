// test_friction_qp.cpp — the frictional step problem (qp/friction_qp.hpp) and its
// solvers (qp/friction_solvers.hpp) against small problems solved by enumeration:
//
//  (i)   Tresca: every combination of {normal free, normal on its bound} × {stick,
//        slip +, slip −} per node gives a linear system; the one whose solution meets
//        the sign conditions is THE solution (the problem is strictly convex).  The
//        semismooth Newton method around pdas, pgs, ipopt and nlopt, pgs on (FQP)
//        itself and Ipopt on split slip variables must find it;
//  (ii)  Coulomb (s = μ λ_N): the same enumeration with the slip rows
//        (S X − r)_T + σ μ (S X − r)_N = 0, linear in X;
//  (iii) s = 0 is the frictionless QP, s = ∞ the bonded one (X_T = X̂_T), both to
//        round-off;
//  (iv)  a method that does not converge says so (NumericalError), bad input is refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/friction_solvers.hpp"
#ifdef CDYN_WITH_IPOPT
#include "cdyn/qp/friction_ipopt.hpp"
#endif
#include "cdyn/qp/kkt.hpp"

using namespace cdyn;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

// Two contact nodes (normal 0, tangential 1; normal 2, tangential 3) and two free
// unknowns, S = Bᵀ B + I SPD with off-diagonal couplings of both signs.
struct Problem {
  BoundQP qp;
  FrictionConditions f;
};

Problem random_problem(unsigned seed, bool coulomb, double law) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 6;
  Eigen::MatrixXd B(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) B(i, j) = 0.4 * u(gen);
  const Eigen::MatrixXd S = B.transpose() * B + Eigen::MatrixXd::Identity(n, n);
  Problem p;
  p.qp.S = S.sparseView(0.0, 0.0);
  p.qp.r = Eigen::VectorXd(n);
  for (int i = 0; i < n; ++i) p.qp.r[i] = u(gen);
  p.qp.r[0] -= 0.5;  // pushed towards the obstacles, more often in contact
  p.qp.r[2] -= 0.5;
  p.qp.lower = Eigen::VectorXd::Constant(n, -kInf);
  p.qp.upper = Eigen::VectorXd::Constant(n, kInf);
  p.qp.lower[0] = 0.1 * u(gen);
  p.qp.lower[2] = 0.1 * u(gen);
  p.f.reference = Eigen::VectorXd::Zero(n);
  p.f.reference[1] = 0.3 * u(gen);
  p.f.reference[3] = 0.3 * u(gen);
  for (int k = 0; k < 2; ++k) {
    FrictionContact c;
    c.normal = 2 * k;
    c.tangential = {2 * k + 1};
    c.coulomb = coulomb;
    if (coulomb)
      c.mu = law;
    else
      c.threshold = law * (1.0 + 0.5 * u(gen));
    p.f.contacts.push_back(c);
  }
  return p;
}

// The solution by enumeration of the 6² combinations; fails the test unless exactly
// one combination meets the sign conditions (to 1e-12).
Eigen::VectorXd enumerate(const Problem& p) {
  const Eigen::MatrixXd S(p.qp.S);
  const Eigen::VectorXd& r = p.qp.r;
  const int n = p.qp.size();
  std::vector<Eigen::VectorXd> found;
  for (int combo = 0; combo < 36; ++combo) {
    Eigen::MatrixXd K = S;
    Eigen::VectorXd b = r;
    int state[2][2];  // [node][0]: normal on bound; [node][1]: 0 stick, 1 slip +, 2 slip −
    for (int k = 0, c = combo; k < 2; ++k, c /= 6) {
      state[k][0] = c % 2;
      state[k][1] = (c / 2) % 3;
    }
    for (int k = 0; k < 2; ++k) {
      const FrictionContact& c = p.f.contacts[k];
      const int N = c.normal, T = c.tangential[0];
      if (state[k][0]) {
        K.row(N).setZero();
        K(N, N) = 1.0;
        b[N] = p.qp.lower[N];
      }
      if (state[k][1] == 0) {
        K.row(T).setZero();
        K(T, T) = 1.0;
        b[T] = p.f.reference[T];
      } else {
        const double sigma = state[k][1] == 1 ? 1.0 : -1.0;
        if (c.coulomb) {  // λ_T = −σ μ λ_N:  (S X − r)_T + σ μ (S X − r)_N = 0
          K.row(T) = S.row(T) + sigma * c.mu * S.row(N);
          b[T] = r[T] + sigma * c.mu * r[N];
        } else {
          b[T] = r[T] - sigma * c.threshold;
        }
      }
    }
    const Eigen::VectorXd X = K.fullPivLu().solve(b);
    const Eigen::VectorXd lambda = S * X - r;
    bool ok = (K * X - b).norm() < 1e-12;
    for (int k = 0; k < 2 && ok; ++k) {
      const FrictionContact& c = p.f.contacts[k];
      const int N = c.normal, T = c.tangential[0];
      const double s = c.coulomb ? c.mu * std::max(lambda[N], 0.0) : c.threshold;
      const double d = X[T] - p.f.reference[T];
      ok = ok && (state[k][0] ? lambda[N] >= -1e-12 : X[N] >= p.qp.lower[N] - 1e-12);
      if (state[k][1] == 0) ok = ok && std::abs(lambda[T]) <= s + 1e-12;
      if (state[k][1] == 1) ok = ok && d >= -1e-12;
      if (state[k][1] == 2) ok = ok && d <= 1e-12;
    }
    if (ok) found.push_back(X);
  }
  EXPECT_GE(found.size(), 1u);
  // (a solution on the boundary of two combinations appears twice, the same X)
  for (const Eigen::VectorXd& X : found) EXPECT_LT((X - found[0]).lpNorm<Eigen::Infinity>(), 1e-10);
  return found.empty() ? Eigen::VectorXd::Zero(n) : found[0];
}

FrictionResult solve(const std::string& method, Problem& p, double tol = 1e-12) {
  FrictionOptions o;
  o.tol = tol;
  if (method == "friction-pgs") return solve_friction_pgs(p.qp, p.f, o);
#ifdef CDYN_WITH_IPOPT
  if (method == "friction-ipopt") return solve_friction_ipopt(p.qp, p.f, o);
#endif
  QPOptions qo;
  qo.tol = 0.1 * tol;
  auto inner = make_step_solver(method, qo);
  return solve_friction_ssn(p.qp, p.f, *inner, o);
}

std::vector<std::string> methods() {
  std::vector<std::string> m = step_solver_names();
  m.push_back("friction-pgs");
#ifdef CDYN_WITH_IPOPT
  m.push_back("friction-ipopt");
#endif
  return m;
}

}  // namespace

// (i) Tresca: 40 random problems, thresholds from 0.05 (mostly slip) to 2 (mostly stick).
TEST(FrictionQP, TrescaMatchesEnumeration) {
  int sticks = 0, slips = 0, fallbacks = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    Problem p = random_problem(seed, false, seed % 4 == 0 ? 0.05 : seed % 4 == 1 ? 0.2 : seed % 4 == 2 ? 0.6 : 2.0);
    const Eigen::VectorXd X = enumerate(p);
    for (const std::string& m : methods()) {
      const FrictionResult res = solve(m, p);
      EXPECT_TRUE(res.converged) << m << " seed " << seed;
      EXPECT_LT((res.qp.X - X).lpNorm<Eigen::Infinity>(), 1e-9) << m << " seed " << seed;
      fallbacks += res.fallbacks;
      if (m == "pdas")
        for (ContactStatus s : res.status) {
          if (s == ContactStatus::Stick) ++sticks;
          if (s == ContactStatus::Slip) ++slips;
        }
    }
  }
  std::printf("Tresca: %d projected Gauss-Seidel fallbacks\n", fallbacks);
  // both regimes are exercised
  EXPECT_GT(sticks, 10);
  EXPECT_GT(slips, 10);
}

// (ii) Coulomb, μ = 0.1 … 0.5 (small enough for a unique solution on these problems).
TEST(FrictionQP, CoulombMatchesEnumeration) {
  int fallbacks = 0;
  for (unsigned seed = 100; seed < 130; ++seed) {
    Problem p = random_problem(seed, true, 0.1 + 0.1 * (seed % 5));
    const Eigen::VectorXd X = enumerate(p);
    for (const std::string& m : methods()) {
      const FrictionResult res = solve(m, p);
      EXPECT_TRUE(res.converged) << m << " seed " << seed;
      EXPECT_LT((res.qp.X - X).lpNorm<Eigen::Infinity>(), 1e-9) << m << " seed " << seed;
      fallbacks += res.fallbacks;
    }
  }
  std::printf("Coulomb: %d projected Gauss-Seidel fallbacks\n", fallbacks);
}

// (iii) s = 0: the frictionless QP; s = ∞: the bonded QP (tangential unknowns fixed).
TEST(FrictionQP, ZeroAndInfiniteThresholds) {
  for (unsigned seed = 200; seed < 210; ++seed) {
    for (double s : {0.0, kInf}) {
      Problem p = random_problem(seed, false, 1.0);
      for (FrictionContact& c : p.f.contacts) c.threshold = s;
      BoundQP plain = p.qp;
      if (s == kInf)
        for (const FrictionContact& c : p.f.contacts)
          plain.lower[c.tangential[0]] = plain.upper[c.tangential[0]] = p.f.reference[c.tangential[0]];
      QPOptions qo;
      qo.tol = 1e-13;
      const QPResult ref = make_step_solver("pdas", qo)->solve(plain);
      for (const std::string& m : methods()) {
        const FrictionResult res = solve(m, p);
        // the same QP solved twice (s = 0, ∞) by different paths, each to its tol
        // (1e-13 for the inner solvers, 1e-12 for (FQP)): measured ≤ 3.6e-14
        EXPECT_LT((res.qp.X - ref.X).lpNorm<Eigen::Infinity>(), 1e-12)
            << m << " s = " << s << " seed " << seed;
        if (s == kInf) {
          for (const FrictionContact& c : p.f.contacts)
            EXPECT_EQ(res.qp.X[c.tangential[0]], p.f.reference[c.tangential[0]]) << m;
        }
      }
    }
  }
}

// The residual is zero at the enumerated solution, and grows with a wrong slip.
TEST(FrictionQP, ResidualMeasuresTheFrictionLaw) {
  Problem p = random_problem(3, false, 0.2);
  const Eigen::VectorXd X = enumerate(p);
  const Eigen::VectorXd D = scaling_diagonal(p.qp);
  const Eigen::VectorXd lambda = Eigen::MatrixXd(p.qp.S) * X - p.qp.r;
  const Eigen::VectorXd s = friction_thresholds(p.f, lambda);
  EXPECT_LT(friction_residual(p.qp, p.f, X, lambda, s, D), 1e-14);
  Eigen::VectorXd Y = X;
  Y[1] += 1e-3;
  const Eigen::VectorXd lambda_Y = Eigen::MatrixXd(p.qp.S) * Y - p.qp.r;
  EXPECT_GT(friction_residual(p.qp, p.f, Y, lambda_Y, s, D), 1e-5);
}

// (iv) Non-convergence is reported, bad input refused.
TEST(FrictionQP, FailuresAreReported) {
  Problem p = random_problem(7, true, 0.4);
  FrictionOptions o;
  o.tol = 1e-12;
  o.max_iterations = 1;
  auto inner = make_step_solver("pdas");
  EXPECT_THROW(solve_friction_ssn(p.qp, p.f, *inner, o), NumericalError);
  EXPECT_THROW(solve_friction_pgs(p.qp, p.f, o), NumericalError);
  o.throw_on_failure = false;
  EXPECT_FALSE(solve_friction_pgs(p.qp, p.f, o).converged);

  Problem bad = random_problem(7, false, 0.4);
  bad.qp.lower[1] = 0.0;  // a bound on a tangential unknown
  EXPECT_THROW(solve_friction_pgs(bad.qp, bad.f, {}), InputError);
  bad = random_problem(7, false, 0.4);
  bad.f.contacts[1].tangential = {1};  // used twice
  EXPECT_THROW(solve_friction_ssn(bad.qp, bad.f, *inner, {}), InputError);
  bad = random_problem(7, false, 0.4);
  bad.f.contacts[0].threshold = -1.0;
  EXPECT_THROW(solve_friction_pgs(bad.qp, bad.f, {}), InputError);
}
