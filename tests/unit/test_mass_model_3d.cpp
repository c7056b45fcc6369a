// test_mass_model_3d.cpp — the mass models on tetrahedra: the pairs M = Bᵀ C⁻¹ B (seed
// eq. 11) and the classical masses, scalar and with three components.
//
// Every expected number comes from mathematics, as in test_mass_model.cpp:
//  - 1_hᵀ M 1_h = ρ|Ω| per component (the L² projection of a constant on an H^h that
//    contains the constants is itself; lumping keeps row sums; T 1_h = 1_h);
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

using namespace cdyn;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

MatrixXd dense_mass(const MassModel& m, int n) {
  if (const auto M = m.matrix()) return MatrixXd(*M);
  MatrixXd D(n, n);
  for (int j = 0; j < n; ++j) D.col(j) = m.momentum(m.velocity(VectorXd::Unit(n, j)));
  return D;
}

// The free dofs (all components) of the vertices of part `part`.
std::vector<int> contact_dofs(const FESpace& W, const DirichletLift& bc, int part) {
  std::vector<int> c;
  for (int v : W.mesh().part_vertices({part}))
    for (int k = 0; k < W.components(); ++k)
      if (const int f = bc.free_index(W.vertex_dof(v, k)); f >= 0) c.push_back(f);
  return c;
}

// The interpolated affine fields 1, x, y, z of each component on the free dofs
// (columns component-major).
MatrixXd affine_fields(const FESpace& W, const DirichletLift& bc) {
  const std::vector<Field> f = {[](const Point&, double) { return 1.0; }, [](const Point& p, double) { return p.x; },
                                [](const Point& p, double) { return p.y; }, [](const Point& p, double) { return p.z; }};
  const Field zero = [](const Point&, double) { return 0.0; };
  const int nc = W.components();
  MatrixXd P(bc.n_free(), 4 * nc);
  for (int k = 0; k < nc; ++k)
    for (int a = 0; a < 4; ++a) {
      std::vector<Field> g(nc, zero);
      g[k] = f[a];
      P.col(4 * k + a) = bc.restrict(W.interpolate(g));
    }
  return P;
}

const Element kContinuous[] = {Element::P1, Element::P1Bubble, Element::P2};

}  // namespace

// M symmetric positive semi-definite and 1ᵀM1 = ρ|Ω| per component, for every pair
// and classical model, on the Kuhn cube and with three components.
TEST(MassModel3D, SymmetricPsdAndTotalMass) {
  const double rho = 2.5;
  const Mesh mesh = unit_cube_mesh(2);
  const int bottom = mesh.part_index("bottom");
  double worst_sym = 0, worst_neg = 0, worst_mass = 0;
  for (int components : {1, 3})
    for (Element e : kContinuous) {
      const FESpace W(mesh, e, components);
      const DirichletLift bc(W, {});
      const MatrixXd P = affine_fields(W, bc);
      std::vector<std::string> specs = {"P0", "P1", "consistent", "redistributed"};
      if (e != Element::P2) specs.push_back("lumped");
      for (const std::string& spec : specs) {
        SCOPED_TRACE(to_string(e) + " " + spec + " components " + std::to_string(components));
        const auto model = make_mass_model(W, bc, spec, rho, contact_dofs(W, bc, bottom));
        const MatrixXd M = dense_mass(*model, bc.n_free());
        const double norm = M.norm();
        const double sym = (M - M.transpose()).norm() / norm;
        const double lmin = Eigen::SelfAdjointEigenSolver<MatrixXd>(0.5 * (M + M.transpose())).eigenvalues()[0];
        worst_sym = std::max(worst_sym, sym);
        worst_neg = std::max(worst_neg, -lmin / norm);
        EXPECT_LE(sym, 1e-14);
        EXPECT_GE(lmin, -1e-13 * norm);
        for (int k = 0; k < components; ++k) {
          const VectorXd one = P.col(4 * k);
          const double mass = one.dot(M * one);
          worst_mass = std::max(worst_mass, std::abs(mass - rho) / rho);
          EXPECT_NEAR(mass, rho * mesh.measure(), 1e-13 * rho);
        }
      }
    }
  std::printf("  worst: asymmetry %.1e, negative eigenvalue %.1e, total-mass error %.1e (relative)\n", worst_sym,
              worst_neg, worst_mass);
}

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
      const std::vector<int> contact = contact_dofs(W, bc, mesh.part_index("bottom"));
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
  const DiagonalCondensation cond(S, lower, upper);
  EXPECT_EQ(cond.n_condensed(), mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) EXPECT_TRUE(cond.condenses(bc.free_index(W.cell_dofs(c)[4])));
  const VectorXd r = VectorXd::LinSpaced(n, -1.0, 2.0).array().cos();
  const VectorXd X = MatrixXd(S).ldlt().solve(r);
  const VectorXd Xv = MatrixXd(cond.S_c()).ldlt().solve(cond.reduce(r));
  EXPECT_LE((cond.expand(Xv, r) - X).norm(), 1e-12 * X.norm());
}
