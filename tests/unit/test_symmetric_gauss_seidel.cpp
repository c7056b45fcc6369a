// test_symmetric_gauss_seidel.cpp — the multicolour symmetric Gauss–Seidel operator of
// linalg/symmetric_gauss_seidel.hpp against dense linear algebra.
//
//  - The colouring is proper (no two coupled unknowns share a colour) and, for the
//    5-point grid Laplacian numbered row by row, the greedy colouring is the red-black
//    one: 2 colours (a fact about that graph: it is bipartite and the natural order
//    colours it alternately).
//  - With L̂ = I + (the entries of Ŝ = D^{-1/2} S D^{-1/2} to earlier colours), restricted
//    to the free unknowns I: multiply_lower = L̂, and apply gives
//    t = L̂⁻ᵀ v and q = L̂⁻¹ Ŝ L̂⁻ᵀ v (Eisenstat's identity, exact algebra), all to round-off
//    of O(1) numbers: 1e-12.
//  - first_residual gives CG's first residuals from a guess y, r = b − S̃y (0 on A) and
//    r̂ = L̂⁻¹ D^{-1/2} r, over all rows and over the free rows alone, as the dense
//    product and inverse give them: 1e-12 again.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "cdyn/linalg/symmetric_gauss_seidel.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// 4 I − (the 5-point stencil) + a mass-like diagonal on an m × m grid, numbered row by row.
cdyn::SparseMatrix grid_matrix(int m) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int a, int b) { return a * m + b; };
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      t.emplace_back(id(a, b), id(a, b), 4.5);
      if (a > 0) t.emplace_back(id(a, b), id(a - 1, b), -1.0);
      if (a + 1 < m) t.emplace_back(id(a, b), id(a + 1, b), -1.0);
      if (b > 0) t.emplace_back(id(a, b), id(a, b - 1), -1.0);
      if (b + 1 < m) t.emplace_back(id(a, b), id(a, b + 1), -1.0);
    }
  cdyn::SparseMatrix S(m * m, m * m);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

// A random symmetric sparse matrix with a positive diagonal (a triangle-mesh-like graph:
// a grid with one diagonal per cell), so that more than two colours are needed.
cdyn::SparseMatrix triangle_grid_matrix(int m, std::mt19937& gen) {
  std::uniform_real_distribution<double> U(0.5, 1.5);
  MatrixXd S = MatrixXd::Zero(m * m, m * m);
  auto id = [m](int a, int b) { return a * m + b; };
  auto couple = [&](int i, int j) { S(i, j) = S(j, i) = -U(gen); };
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      if (a + 1 < m) couple(id(a, b), id(a + 1, b));
      if (b + 1 < m) couple(id(a, b), id(a, b + 1));
      if (a + 1 < m && b + 1 < m) couple(id(a, b), id(a + 1, b + 1));
    }
  for (int i = 0; i < m * m; ++i) S(i, i) = S.row(i).cwiseAbs().sum() + U(gen);
  cdyn::SparseMatrix s = S.sparseView();
  s.makeCompressed();
  return s;
}

void expect_proper_colouring(const cdyn::SparseMatrix& S, const cdyn::SymmetricGaussSeidel& sgs) {
  for (int j = 0; j < S.outerSize(); ++j)
    for (cdyn::SparseMatrix::InnerIterator it(S, j); it; ++it)
      if (it.row() != j) {
        EXPECT_NE(sgs.colour()[it.row()], sgs.colour()[j]) << it.row() << " " << j;
      }
}

TEST(SymmetricGaussSeidel, GreedyColouringOfTheFivePointGridIsRedBlack) {
  const cdyn::SparseMatrix S = grid_matrix(9);
  const cdyn::SymmetricGaussSeidel sgs(S);
  EXPECT_EQ(sgs.colours(), 2);
  expect_proper_colouring(S, sgs);
}

// Ŝ, L̂ and L̂⁻¹ of a held set, dense, on I (rows and columns of A zero, L̂'s diagonal 1 on
// I only), and P the projection onto I.
struct DenseSplitting {
  MatrixXd Shat, Lhat, Lhat_inv, P;
  VectorXd sqrt_d;
};
DenseSplitting dense_splitting(const cdyn::SparseMatrix& S, const cdyn::SymmetricGaussSeidel& sgs,
                               const std::vector<char>& held) {
  const int n = static_cast<int>(S.rows());
  const MatrixXd Sd(S);
  DenseSplitting d;
  d.sqrt_d = Sd.diagonal().cwiseSqrt();
  d.Shat = MatrixXd::Zero(n, n);
  d.Lhat = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (held[i] || held[j]) continue;
      d.Shat(i, j) = Sd(i, j) / (d.sqrt_d[i] * d.sqrt_d[j]);
      if (i == j)
        d.Lhat(i, j) = 1.0;
      else if (sgs.colour()[j] < sgs.colour()[i])
        d.Lhat(i, j) = d.Shat(i, j);
    }
  d.P = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) d.P(i, i) = held[i] ? 0.0 : 1.0;
  d.Lhat_inv = (d.Lhat + (MatrixXd::Identity(n, n) - d.P)).inverse() * d.P;
  return d;
}

TEST(SymmetricGaussSeidel, SweepsAndEisenstatOperatorMatchDenseAlgebra) {
  std::mt19937 gen(11);
  const int m = 7, n = m * m;
  const cdyn::SparseMatrix S = triangle_grid_matrix(m, gen);
  const cdyn::SymmetricGaussSeidel sgs(S);
  expect_proper_colouring(S, sgs);
  EXPECT_GE(sgs.colours(), 3);  // a triangle needs three

  std::vector<char> held(n, 0);
  for (int i = 3; i < n; i += 6) held[i] = 1;
  const DenseSplitting d = dense_splitting(S, sgs, held);
  const MatrixXd& Shat = d.Shat;
  const MatrixXd& Lhat = d.Lhat;
  const MatrixXd& Lhat_inv = d.Lhat_inv;

  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = held[i] ? 0.0 : U(gen);

  VectorXd out(n), t(n), w(n), q(n);
  sgs.multiply_lower(held, v.data(), out.data());
  EXPECT_LE((out - Lhat * v).lpNorm<Eigen::Infinity>(), 1e-12);
  const double vq = sgs.apply(held, v.data(), t.data(), w.data(), q.data());
  const VectorXd t_dense = Lhat_inv.transpose() * v;
  const VectorXd q_dense = Lhat_inv * Shat * t_dense;
  EXPECT_LE((t - t_dense).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LE((q - q_dense).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_NEAR(vq, v.dot(q_dense), 1e-12 * v.squaredNorm());
  for (int i = 0; i < n; ++i)
    if (held[i]) {
      EXPECT_EQ(t[i], 0.0);
      EXPECT_EQ(q[i], 0.0);
    }
}

TEST(SymmetricGaussSeidel, FirstResidualsMatchDenseAlgebraOnAllAndOnFreeRows) {
  std::mt19937 gen(5);
  const int m = 7, n = m * m;
  const cdyn::SparseMatrix S = triangle_grid_matrix(m, gen);
  const cdyn::SymmetricGaussSeidel sgs(S);
  std::vector<char> held(n, 0);
  for (int i = 1; i < n; i += 4) held[i] = 1;
  const DenseSplitting d = dense_splitting(S, sgs, held);

  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd b(n), y(n), y_hat(n);
  for (int i = 0; i < n; ++i) {
    b[i] = U(gen);
    y[i] = held[i] ? b[i] : U(gen);
    y_hat[i] = held[i] ? 0.0 : d.sqrt_d[i] * y[i];
  }
  // r = b − S̃y on I: S's rows on I against y's free entries; 0 on A
  const VectorXd y_free = d.P * y;
  const VectorXd r_dense = d.P * (b - MatrixXd(S) * y_free);
  const VectorXd r_hat_dense = d.Lhat_inv * r_dense.cwiseQuotient(d.sqrt_d);

  VectorXd u(n), r_hat(n), r(n);
  sgs.first_residual(held, b.data(), y_hat.data(), u.data(), r_hat.data(), r.data());
  EXPECT_LE((r - r_dense).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LE((r_hat - r_hat_dense).lpNorm<Eigen::Infinity>(), 1e-12);

  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!held[i]) free.push_back(i);
  VectorXd u2 = VectorXd::Zero(n), r_hat2 = VectorXd::Zero(n), r2 = VectorXd::Zero(n);
  sgs.first_residual(sgs.free_rows(free), b.data(), y_hat.data(), u2.data(), r_hat2.data(), r2.data());
  EXPECT_LE((r2 - r_dense).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LE((r_hat2 - r_hat_dense).lpNorm<Eigen::Infinity>(), 1e-12);
  for (int i = 0; i < n; ++i)
    if (held[i]) {
      EXPECT_EQ(r[i], 0.0);
      EXPECT_EQ(r_hat[i], 0.0);
      EXPECT_EQ(r2[i], 0.0);
    }
}

}  // namespace
