// test_qp_rotation.cpp — nodal Signorini on inclined planes as bounds after the node-local
// rotation of problems/nodal_rotation.hpp.
//
// Reference: the same QP with the general linear constraints n_k · u_k ≤ g_k, solved by
// enumerating which constraints are active (2^K dense KKT systems [[S, Gᵀ], [G, 0]]),
// keeping the one that is feasible with multipliers μ ≥ 0 — no rotation involved.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/step_solver.hpp"
#include "cdyn/problems/nodal_rotation.hpp"
#include "cdyn/qp/rotated_qp.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
constexpr double inf = std::numeric_limits<double>::infinity();

struct Plane {
  int node;
  double nx, ny, gap;
};

// Exact solution of min ½uᵀSu − rᵀu s.t. n_k·u_node ≤ gap_k, by enumeration.
VectorXd enumerate(const MatrixXd& S, const VectorXd& r, const std::vector<Plane>& planes, VectorXd& mu_out) {
  const int n = static_cast<int>(r.size()), K = static_cast<int>(planes.size());
  for (int mask = 0; mask < (1 << K); ++mask) {
    std::vector<int> act;
    for (int k = 0; k < K; ++k)
      if (mask >> k & 1) act.push_back(k);
    const int m = static_cast<int>(act.size());
    MatrixXd KKT = MatrixXd::Zero(n + m, n + m);
    VectorXd b = VectorXd::Zero(n + m);
    KKT.topLeftCorner(n, n) = S;
    b.head(n) = r;
    for (int a = 0; a < m; ++a) {
      const Plane& p = planes[act[a]];
      KKT(n + a, 2 * p.node) = KKT(2 * p.node, n + a) = p.nx;
      KKT(n + a, 2 * p.node + 1) = KKT(2 * p.node + 1, n + a) = p.ny;
      b[n + a] = p.gap;
    }
    const VectorXd y = KKT.fullPivLu().solve(b);  // S u + Gᵀμ = r, G u = gap
    const VectorXd u = y.head(n);
    bool ok = true;
    for (int a = 0; a < m; ++a) ok = ok && y[n + a] >= -1e-12;
    for (const Plane& p : planes) ok = ok && p.nx * u[2 * p.node] + p.ny * u[2 * p.node + 1] <= p.gap + 1e-12;
    if (ok) {
      mu_out = VectorXd::Zero(K);
      for (int a = 0; a < m; ++a) mu_out[act[a]] = y[n + a];
      return u;
    }
  }
  ADD_FAILURE() << "no KKT point";
  return VectorXd::Zero(n);
}

// A 2D "spring network": N nodes in a chain, each with a spring to the next and to the
// ground, in both directions and coupled (so S mixes u_x and u_y).
MatrixXd chain(int N, std::mt19937& gen) {
  std::uniform_real_distribution<double> U(0.2, 1.0), angle(0.0, M_PI);
  MatrixXd S = MatrixXd::Zero(2 * N, 2 * N);
  for (int a = 0; a < N; ++a) {
    S.block(2 * a, 2 * a, 2, 2) += U(gen) * MatrixXd::Identity(2, 2);
    if (a + 1 < N) {
      const double t = angle(gen), k = 5 * U(gen);
      Eigen::Vector2d d(std::cos(t), std::sin(t));
      const MatrixXd kdd = k * d * d.transpose();
      S.block(2 * a, 2 * a, 2, 2) += kdd;
      S.block(2 * a + 2, 2 * a + 2, 2, 2) += kdd;
      S.block(2 * a, 2 * a + 2, 2, 2) -= kdd;
      S.block(2 * a + 2, 2 * a, 2, 2) -= kdd;
    }
  }
  return S;
}

TEST(QPRotation, InclinedSignoriniMatchesTheConstrainedQP) {
  int active_planes = 0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::mt19937 gen(seed);
    const int N = 6;
    const MatrixXd S = chain(N, gen);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    VectorXd r(2 * N);
    for (int i = 0; i < 2 * N; ++i) r[i] = 3 * U(gen);
    // planes at 30°, 120° and 200°, gaps small so that some are active
    const std::vector<Plane> planes = {{0, std::cos(M_PI / 6), std::sin(M_PI / 6), 0.1},
                                       {2, std::cos(2 * M_PI / 3), std::sin(2 * M_PI / 3), 0.05},
                                       {5, std::cos(10 * M_PI / 9), std::sin(10 * M_PI / 9), 0.0}};
    VectorXd mu;
    const VectorXd exact = enumerate(S, r, planes, mu);

    cdyn::NodalRotation rot;
    for (const Plane& p : planes) rot.nodes.push_back({2 * p.node, 2 * p.node + 1, p.nx, p.ny});
    cdyn::BoundQP qp;
    qp.S = S.sparseView();
    qp.S.makeCompressed();
    qp.r = r;
    qp.lower = VectorXd::Constant(2 * N, -inf);
    qp.upper = VectorXd::Constant(2 * N, inf);
    const cdyn::SparseMatrix R = cdyn::rotation_matrix(rot, 2 * N);
    cdyn::BoundQP local = cdyn::rotate(qp, R);
    for (const Plane& p : planes) local.upper[2 * p.node] = p.gap;  // normal component ≤ gap

    for (const std::string& name : cdyn::step_solver_names()) {
      auto solver = cdyn::make_step_solver(name, cdyn::QPOptions{});
      const cdyn::QPResult res = cdyn::rotate_back(R, solver->solve(local));
      EXPECT_LE((res.X - exact).lpNorm<Eigen::Infinity>(), 1e-8) << name << " seed " << seed;
      // the reaction in global components is −μ_k n_k at the constrained nodes, 0 elsewhere
      VectorXd expected = VectorXd::Zero(2 * N);
      for (std::size_t k = 0; k < planes.size(); ++k) {
        expected[2 * planes[k].node] = -mu[k] * planes[k].nx;
        expected[2 * planes[k].node + 1] = -mu[k] * planes[k].ny;
      }
      EXPECT_LE((res.reaction - expected).lpNorm<Eigen::Infinity>(), 1e-8) << name << " seed " << seed;
      EXPECT_LE((res.reaction - (S * res.X - r)).lpNorm<Eigen::Infinity>(), 1e-12) << name;
    }
    active_planes += static_cast<int>((mu.array() > 1e-12).count());
  }
  // the planes must actually be in contact in these cases, or the test proves little
  EXPECT_GE(active_planes, 5);
  std::cout << "active planes over the 5 cases: " << active_planes << " of 15\n";
}

TEST(QPRotation, RotationIsOrthogonalAndRoundTrips) {
  cdyn::NodalRotation rot;
  rot.nodes.push_back({0, 1, 3.0, 4.0});  // normalized to (0.6, 0.8)
  rot.nodes.push_back({4, 5, -1.0, 0.0});
  const cdyn::SparseMatrix R = cdyn::rotation_matrix(rot, 6);
  const MatrixXd Rd(R);
  EXPECT_LE((Rd.transpose() * Rd - MatrixXd::Identity(6, 6)).norm(), 1e-15);
  VectorXd u(6);
  u << 0.6, 0.8, 7, 8, 1, 2;
  const VectorXd local = cdyn::to_local(rot, u);
  EXPECT_NEAR(local[0], 1.0, 1e-15);  // n·u with u = n
  EXPECT_NEAR(local[1], 0.0, 1e-15);  // t·u
  EXPECT_NEAR(local[4], -1.0, 1e-15);
  EXPECT_NEAR(local[5], -2.0, 1e-15);  // t = (0, −1)
  EXPECT_LE((cdyn::to_global(rot, local) - u).norm(), 1e-15);
  EXPECT_LE((Rd.transpose() * u - local).norm(), 1e-15);

  cdyn::NodalRotation bad;
  bad.nodes.push_back({0, 1, 0.0, 0.0});
  EXPECT_THROW(cdyn::rotation_matrix(bad, 4), cdyn::InputError);
  cdyn::NodalRotation twice;
  twice.nodes.push_back({0, 1, 1.0, 0.0});
  twice.nodes.push_back({1, 2, 1.0, 0.0});
  EXPECT_THROW(cdyn::rotation_matrix(twice, 4), cdyn::InputError);
}

TEST(QPRotation, SaddleFormRotatesLikeTheExplicitS) {
  // A = chain stiffness, B = I-like coupling, C = tridiagonal mass: rotate both forms.
  std::mt19937 gen(7);
  const int N = 5;
  const MatrixXd A = chain(N, gen);
  MatrixXd C = MatrixXd::Zero(2 * N, 2 * N), B = MatrixXd::Zero(2 * N, 2 * N);
  for (int i = 0; i < 2 * N; ++i) {
    C(i, i) = 4.0 / 6.0;
    if (i + 2 < 2 * N) C(i, i + 2) = C(i + 2, i) = 1.0 / 6.0;
    B(i, i) = 0.5;
    if (i + 2 < 2 * N) B(i, i + 2) = B(i + 2, i) = 0.25;
  }
  cdyn::SaddleForm f;
  f.A = A.sparseView();
  f.B = B.sparseView();
  f.C = C.sparseView();
  f.c = 2.0;
  const MatrixXd S = A + f.c * B.transpose() * C.inverse() * B;
  VectorXd r(2 * N);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int i = 0; i < 2 * N; ++i) r[i] = 3 * U(gen);
  cdyn::NodalRotation rot;
  rot.nodes.push_back({2, 3, std::cos(0.7), std::sin(0.7)});
  rot.nodes.push_back({6, 7, std::cos(2.0), std::sin(2.0)});

  cdyn::BoundQP as_saddle, as_explicit;
  as_saddle.saddle = f;
  as_explicit.S = S.sparseView();
  for (cdyn::BoundQP* qp : {&as_saddle, &as_explicit}) {
    qp->r = r;
    qp->lower = VectorXd::Constant(2 * N, -inf);
    qp->upper = VectorXd::Constant(2 * N, inf);
  }
  const cdyn::SparseMatrix R = cdyn::rotation_matrix(rot, 2 * N);
  cdyn::BoundQP ls = cdyn::rotate(as_saddle, R), le = cdyn::rotate(as_explicit, R);
  for (cdyn::BoundQP* qp : {&ls, &le}) {
    qp->upper[2] = 0.0;
    qp->upper[6] = 0.0;
  }
  // Direct solves only (the saddle form is solved by LU anyway): the two forms agree to
  // round-off, while PDAS's CG stops at the KKT tolerance (a residual, not an error bound).
  cdyn::QPOptions direct;
  direct.pdas_cg_iterations = 0;
  auto pdas = cdyn::make_step_solver("pdas", direct);
  const cdyn::QPResult rs = pdas->solve(ls), re = pdas->solve(le);
  EXPECT_LE((rs.X - re.X).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_EQ(rs.active, re.active);
  EXPECT_FALSE(rs.active.empty());
}

}  // namespace
