// test_mass_model_3d.cpp — the mass models on tetrahedra: the pairs M = Bᵀ C⁻¹ B (seed
// eq. 11) and the classical masses, scalar and with three components.
//
// (1_hᵀ M 1_h = ρ|Ω| and M symmetric positive semi-definite for every model on the cube,
// scalar and with three components: test_mass_model.cpp, SymmetricPsdAndTotalMass.)
// Every expected number comes from mathematics, as in test_mass_model.cpp:
//  - P1/P1 is the consistent mass;
//  - mass redistribution keeps the moments of order ≤ 2, Pᵀ M_red Q = Pᵀ M_ff Q for P, Q
//    in {1, x, y, z}, and removes the inertia of the contact dofs;
//  - P2 has vertex functions of negative integral in 3D (∫ λ(2λ − 1) = −|K|/20), so
//    row-sum lumping is refused;
//  - with H^h = P0 the bubbles of P1+ are the unknowns the step QP condenses, one per
//    cell (qp/condensation.hpp), also on tetrahedra.
// Tolerances: exact identities on matrices of a few hundred rows; the worst round-off
// measured is printed by each test and the bounds leave ≥ 10× above it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/qp/condensation.hpp"
#include "mass_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::testing;  // mass_fixtures.hpp
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

const Element kContinuous[] = {Element::P1, Element::P1Bubble, Element::P2};

}  // namespace

TEST(MassModel3D, P1OverP1IsTheConsistentMassAndP2IsNotLumped) {
  const Mesh mesh = unit_cube_mesh(2);
  for (int components : {1, 3}) {
    const FESpace W(mesh, Element::P1, components);
    const DirichletLift bc(W, {mesh.part_index("left"), mesh.part_index("top")});
    const MatrixXd Mp = dense_mass(*make_mass_model(W, bc, "P1/P1", 1.7), bc.n_free());
    const MatrixXd Mc = dense_mass(*make_mass_model(W, bc, "consistent", 1.7), bc.n_free());
    EXPECT_LE((Mp - Mc).norm(), 1e-13 * Mc.norm());
  }
  const FESpace W2(mesh, Element::P2);
  EXPECT_THROW(make_mass_model(W2, DirichletLift(W2, {}), "lumped", 1.0), InputError);
}

// Redistribution (Khenous–Laborde–Renard): zero rows and columns at the contact dofs,
// the moments of order ≤ 2 of the consistent mass unchanged (P, Q affine in x, y, z).
TEST(MassModel3D, RedistributionKeepsMomentsAndRemovesContactInertia) {
  const Mesh mesh = unit_cube_mesh(3);
  double worst = 0.0;
  for (int components : {1, 3})
    for (Element e : kContinuous) {
      SCOPED_TRACE(to_string(e) + " components " + std::to_string(components));
      const FESpace W(mesh, e, components);
      const DirichletLift bc(W, {mesh.part_index("top")});
      const std::vector<int> contact = contact_dofs(W, bc, {"bottom"});
      const MatrixXd Mr = dense_mass(*make_mass_model(W, bc, "redistributed", 1.0, contact), bc.n_free());
      const MatrixXd Mc = dense_mass(*make_mass_model(W, bc, "consistent", 1.0), bc.n_free());
      for (int i : contact) {
        EXPECT_EQ(Mr.row(i).norm(), 0.0);
        EXPECT_EQ(Mr.col(i).norm(), 0.0);
      }
      const MatrixXd P = affine_fields(W, bc);
      const MatrixXd moments = P.transpose() * Mr * P, expected = P.transpose() * Mc * P;
      const double defect = (moments - expected).norm() / expected.norm();
      worst = std::max(worst, defect);
      EXPECT_LE(defect, 1e-12);
    }
  std::printf("  redistribution: moments of order <= 2 kept to %.1e (relative)\n", worst);
}

// P1+/P0: S = A + k M has one bubble per cell, unbounded, coupled with the four
// vertices of its cell only (A_vb = 0; M_vb through C = diag|K|): the step QP
// condenses exactly those, and the condensed system solves the full one.
TEST(MassModel3D, TheBubblesOfP1PlusP0AreCondensed) {
  const Mesh mesh = unit_cube_mesh(2);
  const FESpace W(mesh, Element::P1Bubble);
  const DirichletLift bc(W, {mesh.part_index("top")});
  const SparseMatrix A = bc.restrict(assemble_laplace(W));
  const auto model = make_mass_model(W, bc, "P1+/P0", 1.0);
  const SparseMatrix S = A + 400.0 * *model->matrix();
  const int n = bc.n_free();
  const double inf = std::numeric_limits<double>::infinity();
  VectorXd lower = VectorXd::Constant(n, -inf), upper = VectorXd::Constant(n, inf);
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (const int f = bc.free_index(W.vertex_dof(v)); f >= 0) lower[f] = 0.0;  // the obstacle u ≥ 0
  const StaticCondensation cond(S, lower, upper);
  EXPECT_EQ(cond.n_condensed(), mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) EXPECT_TRUE(cond.condenses(bc.free_index(W.cell_dofs(c)[4])));
  const VectorXd r = VectorXd::LinSpaced(n, -1.0, 2.0).array().cos();
  const VectorXd X = MatrixXd(S).ldlt().solve(r);
  const VectorXd Xv = MatrixXd(cond.S_c()).ldlt().solve(cond.reduce(r));
  EXPECT_LE((cond.expand(Xv, r) - X).norm(), 1e-12 * X.norm());
}
