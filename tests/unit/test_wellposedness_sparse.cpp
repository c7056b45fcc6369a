// test_wellposedness_sparse.cpp — the sparse check of condition (12)
// (wellposedness/condition12_sparse.hpp) against the dense reference (condition12.hpp),
// and its parts: the Lanczos process, the inertia certificate of the shifted Gram
// matrix, the rank of B.
//
// Expected values: the dense method's β on every case of test_wellposedness.cpp
// (agreement to 1e-8 relative asked, measured ≤ 3e-15), exact zeros where counting
// decides (dim Ker B < N_g), and hand-sized matrices with a closed form.  No timings here:
// bench/bench_condition12.cpp measures those.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/wellposedness/condition12.hpp"
#include "cdyn/wellposedness/condition12_sparse.hpp"
#include "cdyn/wellposedness/lanczos.hpp"
#include "cdyn/wellposedness/row_basis.hpp"
#include "cdyn/wellposedness/shifted_gram.hpp"
#include "wellposedness_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::testing;  // wellposedness_fixtures.hpp

namespace {

// The largest |β_sparse − β_dense| / β_dense over the cases compared so far.
double worst_relative = 0.0;

// Both methods on the same setup: the same kernel dimension and decision, β to 1e-8
// relative (absolute where β = 0), and exactly 0 where counting decides.
void expect_agreement(const std::string& where, const Mesh& mesh, const std::string& spec,
                      WellPosednessSetup setup) {
  setup.method = Condition12Method::dense;
  const WellPosedness d = condition12_on(mesh, MassSpec::parse(spec), setup);
  setup.method = Condition12Method::sparse;
  const WellPosedness s = condition12_on(mesh, MassSpec::parse(spec), setup);
  std::printf("[condition 12] %-26s %-14s N_W %5d dim Ker B %5d N_g %4d  dense %.16e  sparse %.16e  (%d fact., %d solves)\n",
              where.c_str(), spec.c_str(), s.n_W, s.dim_ker_B, s.n_g, d.beta, s.beta, s.factorizations, s.solves);
  EXPECT_EQ(s.method, "sparse");
  EXPECT_EQ(s.dim_ker_B, d.dim_ker_B) << where << " " << spec;
  EXPECT_EQ(s.satisfied, d.satisfied) << where << " " << spec;
  if (d.dim_ker_B < d.n_g) {
    EXPECT_EQ(s.beta, 0.0) << where << " " << spec;
    EXPECT_EQ(s.factorizations, 0) << "counting decides, no eigensolver";
  } else if (d.beta > kBetaTolerance) {
    const double rel = std::abs(s.beta - d.beta) / d.beta;
    worst_relative = std::max(worst_relative, rel);
    EXPECT_LE(rel, 1e-8) << where << " " << spec;
  } else {
    EXPECT_LE(s.beta, 1e-8) << where << " " << spec;  // G Z rank deficient: round-off of each method
  }
}

}  // namespace

// Every pair and classical mass of the seed's membrane table (n = 10, 20), the full P1
// velocity spaces, the boundary-contact cases (membrane, bar, elasticity with normals)
// and the unstructured L-shape.
TEST(Condition12Sparse, AgreesWithDenseOnEveryCase) {
  for (int n : {10, 20}) {
    const Mesh mesh = unit_square_mesh(n);
    const WellPosednessSetup setup = clamped_membrane_setup(mesh);
    const std::string where = "membrane n=" + std::to_string(n);
    for (const std::string spec : {"P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1", "P2/P0", "consistent", "lumped"})
      expect_agreement(where, mesh, spec, setup);
    // Full P1 velocity space: P1+/P1 then has G Z exactly rank deficient (β = 0 with
    // dim Ker B ≥ N_g, docs/semi_discretization.md), P2/P1 does not.
    for (const std::string pair : {"P1+/P1", "P2/P1"}) {
      const FESpace W(mesh, element_from_string(pair.substr(0, pair.find('/'))));
      const DirichletLift bc(W, setup.dirichlet_parts);
      const SparseMatrix B = mixed_blocks(W, bc, Element::P1, 1.0, false).B;
      const SparseMatrix G = vertex_constraint_matrix(W, bc, setup.constrained_vertices);
      const WellPosedness d = condition12(B, G, Condition12Method::dense);
      const WellPosedness s = condition12(B, G, Condition12Method::sparse);
      std::printf("[condition 12] %-26s %-14s dense %.3e  sparse %.3e\n", where.c_str(), (pair + "(full H)").c_str(),
                  d.beta, s.beta);
      EXPECT_EQ(s.dim_ker_B, d.dim_ker_B);
      EXPECT_EQ(s.satisfied, d.satisfied) << pair;
      if (d.satisfied)
        EXPECT_LE(std::abs(s.beta - d.beta), 1e-8 * d.beta);
      else
        EXPECT_LE(s.beta, 1e-13);  // measured 3e-14: the Ritz vector's error, unsquared
    }
  }
  {
    const Mesh mesh = unit_square_mesh(10);
    WellPosednessSetup setup;
    setup.dirichlet_parts = parts(mesh, {"top"});
    setup.constrained_vertices = mesh.part_vertices(parts(mesh, {"bottom"}));
    for (const std::string spec : {"P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1", "consistent", "redistributed"})
      expect_agreement("membrane, contact bottom", mesh, spec, setup);
  }
  {
    const Mesh mesh = interval_mesh(40);
    WellPosednessSetup setup;
    setup.dirichlet_parts = parts(mesh, {"right"});
    setup.constrained_vertices = {0};  // N_g = 1: the Krylov space is invariant at once
    for (const std::string spec : {"P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1", "consistent", "redistributed"})
      expect_agreement("bar, contact x=0", mesh, spec, setup);
  }
  {
    const Mesh mesh = unit_square_mesh(8);
    WellPosednessSetup setup;
    setup.dirichlet_parts = parts(mesh, {"top"});
    setup.constrained_vertices = mesh.part_vertices(parts(mesh, {"bottom"}));
    setup.components = 2;
    setup.normal = Point{0.6, -0.8};  // an inclined unit normal: both components in each row of G
    for (const std::string spec : {"P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1", "consistent", "redistributed"})
      expect_agreement("elasticity, contact bottom", mesh, spec, setup);
  }
  const std::string geo = std::string(CDYN_SOURCE_DIR) + "/data/geo/lshape.geo";
  if (std::filesystem::exists(geo)) {
    const Mesh mesh = read_mesh(geo);
    WellPosednessSetup setup;
    for (int p = 0; p < static_cast<int>(mesh.part_names.size()); ++p) setup.dirichlet_parts.push_back(p);
    setup.constrained_vertices = all_vertices(mesh);
    for (const std::string spec : {"P1+/P0", "P1+/P1", "P2/P1", "P2/P0"}) expect_agreement("lshape.geo", mesh, spec, setup);
  }
  std::printf("[condition 12] largest relative difference sparse/dense where beta > 0: %.1e\n", worst_relative);
}

// Hand-sized cases.  B = [1 1 0 0; 1 1 0 0; 0 0 1 −1] has a repeated row (rank 2, so the
// QR fallback of row_basis runs): Ker B = span{(1,−1,0,0), (0,0,1,1)}/√2.
TEST(Condition12Sparse, HandComputedBetaWithDependentRows) {
  const SparseMatrix B = sparse((Eigen::MatrixXd(3, 4) << 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, -1).finished());
  const RowBasis basis = row_basis(rows_scaled_to_unit_max(B));
  EXPECT_EQ(basis.rank, 2);
  ASSERT_EQ(basis.rows.size(), 2u);
  EXPECT_EQ(basis.rows[1], 2);  // row 2 is needed; rows 0 and 1 are the same
  // G = [e_1ᵀ; e_3ᵀ]: G Z = I/√2, β = 1/√2.
  WellPosedness r = condition12_sparse(B, sparse((Eigen::MatrixXd(2, 4) << 1, 0, 0, 0, 0, 0, 1, 0).finished()));
  EXPECT_EQ(r.dim_ker_B, 2);
  EXPECT_NEAR(r.beta, 1.0 / std::sqrt(2.0), 1e-14);
  // G = [e_1ᵀ; e_2ᵀ]: G Z = [[1, 0], [−1, 0]]/√2 has rank 1 although dim Ker B = N_g.
  r = condition12_sparse(B, sparse((Eigen::MatrixXd(2, 4) << 1, 0, 0, 0, 0, 1, 0, 0).finished()));
  std::printf("[condition 12] exactly rank-deficient G Z, sparse: computed beta %.1e\n", r.beta);
  EXPECT_LE(r.beta, 1e-14);
  EXPECT_FALSE(r.satisfied);
  // Three constraints on a two-dimensional kernel: β = 0 by counting.
  r = condition12_sparse(B, sparse(Eigen::MatrixXd::Identity(3, 4)));
  EXPECT_EQ(r.beta, 0.0);
  // No constraint.
  r = condition12_sparse(B, SparseMatrix(0, 4));
  EXPECT_TRUE(std::isinf(r.beta));
}

// P2/P0 on the structured square: B loses one rank (the two-colouring of the triangles,
// docs/semi_discretization.md), found by the QR fallback; β = 1.
TEST(Condition12Sparse, RankDeficientB) {
  const Mesh mesh = unit_square_mesh(12);
  const FESpace W(mesh, Element::P2);
  const DirichletLift bc(W, parts(mesh, {"bottom", "right", "top", "left"}));
  const SparseMatrix B = mixed_blocks(W, bc, Element::P0, 1.0).B;
  const RowBasis basis = row_basis(rows_scaled_to_unit_max(B));
  EXPECT_EQ(basis.rank, B.rows() - 1);
  EXPECT_EQ(static_cast<int>(basis.rows.size()), basis.rank);
  const WellPosedness r = condition12_sparse(B, vertex_constraint_matrix(W, bc, all_vertices(mesh)));
  EXPECT_EQ(r.dim_ker_B, r.n_W - r.n_H + 1);
  EXPECT_NEAR(r.beta, 1.0, 1e-13);
}

// The certificate: M(σ) = [B; G][B; G]ᵀ − σE is positive definite iff σ < β², on P1+/P0
// whose β has a closed form (test_wellposedness.cpp); and its solve is (G P Gᵀ − σ)⁻¹
// with W = P Gᵀ Q in Ker B.
TEST(Condition12Sparse, ShiftedGramCertifiesShifts) {
  const Mesh mesh = unit_square_mesh(10);
  const FESpace W(mesh, Element::P1Bubble);
  const DirichletLift bc(W, parts(mesh, {"bottom", "right", "top", "left"}));
  const SparseMatrix B = rows_scaled_to_unit_max(mixed_blocks(W, bc, Element::P0, 1.0).B);
  const SparseMatrix G = vertex_constraint_matrix(W, bc, all_vertices(mesh));
  const double beta2 = std::pow(condition12(B, G, Condition12Method::dense).beta, 2);
  ShiftedGram gram(B, G);
  EXPECT_TRUE(gram.factorize(beta2 * (1.0 - 1e-9)));
  EXPECT_FALSE(gram.factorize(beta2 * (1.0 + 1e-9)));
  ASSERT_TRUE(gram.factorize(-0.5));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(G.rows(), -1.0, 2.0);
  Eigen::VectorXd Wq;
  const Eigen::VectorXd Q = gram.solve(q, &Wq);
  // Dense reference: P = I − Bᵀ (B Bᵀ)⁻¹ B.
  const Eigen::MatrixXd Bd(B), Gd(G);
  const Eigen::MatrixXd P =
      Eigen::MatrixXd::Identity(B.cols(), B.cols()) - Bd.transpose() * (Bd * Bd.transpose()).ldlt().solve(Bd);
  const Eigen::MatrixXd A = Gd * P * Gd.transpose() + 0.5 * Eigen::MatrixXd::Identity(G.rows(), G.rows());
  EXPECT_LE((A * Q - q).norm(), 1e-12 * q.norm());
  EXPECT_LE((Wq - P * Gd.transpose() * Q).norm(), 1e-12 * Wq.norm());
  EXPECT_LE((Bd * Wq).norm(), 1e-12 * Wq.norm());
  EXPECT_EQ(gram.factorizations(), 3);
  EXPECT_EQ(gram.solves(), 1);
}

// Lanczos on a diagonal operator: the largest eigenvalue and its eigenvector, with a
// clustered top (the situation of G P Gᵀ's bottom) and with an invariant Krylov space.
TEST(Condition12Sparse, LanczosLargest) {
  const int n = 200;
  Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  d[n - 1] = 3.0;  // well separated
  const auto T = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return d.cwiseProduct(x); };
  const Eigen::VectorXd start = Eigen::VectorXd::Ones(n);
  const auto never = [](const LanczosPair&) { return false; };
  LanczosPair p = lanczos_largest(T, start, 30, never);
  EXPECT_NEAR(p.value, 3.0, 1e-13);
  EXPECT_NEAR(std::abs(p.vector[n - 1]), 1.0, 1e-10);
  EXPECT_LE(p.residual, 1e-10);
  EXPECT_EQ(p.steps, 30);
  // A stopping rule is honoured.
  p = lanczos_largest(T, start, 30, [](const LanczosPair& q) { return q.residual < 1e-6 * q.value; });
  EXPECT_LT(p.steps, 30);
  EXPECT_NEAR(p.value, 3.0, 1e-6);
  // Fewer dimensions than steps: the space becomes invariant, exact pair.
  const Eigen::VectorXd small = (Eigen::VectorXd(3) << 1.0, 2.0, 5.0).finished();
  p = lanczos_largest([&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return small.cwiseProduct(x); },
                      Eigen::VectorXd::Ones(3), 30, never);
  EXPECT_LE(p.steps, 3);
  EXPECT_NEAR(p.value, 5.0, 1e-14);
  EXPECT_EQ(p.residual, 0.0);
}
