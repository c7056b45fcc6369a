// test_symmetric_gauss_seidel.cpp — the multicolour symmetric Gauss–Seidel operator of
// linalg/symmetric_gauss_seidel.hpp against dense linear algebra.
//
//  - The colouring is proper (no two coupled unknowns share a colour) and, for the
//    5-point grid Laplacian numbered row by row, the greedy colouring is the red-black
//    one: 2 colours (a fact about that graph: it is bipartite and the natural order
//    colours it alternately).
//  - With L̂ = I + (the entries of Ŝ = D^{-1/2} S D^{-1/2} to earlier colours), restricted
//    to the free unknowns I: solve_lower = L̂⁻¹, multiply_lower = L̂, and apply gives
//    t = L̂⁻ᵀ v and q = L̂⁻¹ Ŝ L̂⁻ᵀ v (Eisenstat's identity, exact algebra), all to round-off
//    of O(1) numbers: 1e-12.
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

TEST(SymmetricGaussSeidel, SweepsAndEisenstatOperatorMatchDenseAlgebra) {
  std::mt19937 gen(11);
  const int m = 7, n = m * m;
  const cdyn::SparseMatrix S = triangle_grid_matrix(m, gen);
  const cdyn::SymmetricGaussSeidel sgs(S);
  expect_proper_colouring(S, sgs);
  EXPECT_GE(sgs.colours(), 3);  // a triangle needs three

  std::vector<char> held(n, 0);
  for (int i = 3; i < n; i += 6) held[i] = 1;
  // dense Ŝ and L̂ on I (rows and columns of A zero, L̂'s diagonal 1 on I only)
  const MatrixXd Sd(S);
  const VectorXd s = Sd.diagonal().cwiseSqrt();
  MatrixXd Shat = MatrixXd::Zero(n, n), Lhat = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (held[i] || held[j]) continue;
      Shat(i, j) = Sd(i, j) / (s[i] * s[j]);
      if (i == j)
        Lhat(i, j) = 1.0;
      else if (sgs.colour()[j] < sgs.colour()[i])
        Lhat(i, j) = Shat(i, j);
    }
  MatrixXd P = MatrixXd::Zero(n, n);  // the projection onto I, to invert L̂ on I only
  for (int i = 0; i < n; ++i) P(i, i) = held[i] ? 0.0 : 1.0;
  const MatrixXd Lhat_inv = (Lhat + (MatrixXd::Identity(n, n) - P)).inverse() * P;

  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = held[i] ? 0.0 : U(gen);

  VectorXd out(n), t(n), w(n), q(n);
  sgs.solve_lower(held, v.data(), out.data());
  EXPECT_LE((out - Lhat_inv * v).lpNorm<Eigen::Infinity>(), 1e-12);
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

}  // namespace
