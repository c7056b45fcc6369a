// test_materials.cpp — bodies of several materials: ρ, λ, μ constant per cell
// (fe/cell_coefficient.hpp) in the mass models, the stiffness and the gravity load,
// and materials by mesh region in build_elastic_contact.
//
// The closed-form checks, on the column [0, 1] × [0, 2] cut at y = 1 into two regions
// ("soft" below, "stiff" above; the interface is a grid line):
//  - the mass of every model, 1ᵀ M 1 = Σ_r ρ_r |Ω_r| per component (pairs P1/P1, P1/P0,
//    P1+/P0, P1+/P1, P2/P1, P2/P0; consistent, lumped, redistributed);
//  - the weight, 1ᵀ L = g_k Σ_r ρ_r |Ω_r|;
//  - the static confined compression (an oedometer): sides on rollers (u_x = 0), the
//    base fixed, the top pressed by p.  The solution is one-dimensional, u_x = 0 and
//    u_y piecewise linear with σ_yy = −p in both layers, so each layer is a spring of
//    stiffness M_r / h_r with the oedometric modulus M_r = λ_r + 2μ_r, in series:
//        u_y(top) = −p (h_soft / M_soft + h_stiff / M_stiff),
//    and σ_xx = σ_zz = −p λ_r / M_r jumps across the interface.  P1, P1+ and P2 contain
//    it, so it comes out to round-off (measured: u to 2.6e-14, 4.3e-14, 1.4e-13 of
//    |u_y(top)|, σ to 5.2e-14, 8.3e-14, 1.6e-13 of p for P1, P1+, P2; tolerance 1e-12,
//    the moduli differ by 35 and the factorization loses that much).
// Measured masses: 1ᵀM1 to 4e-16 (P1/P1, P1/P0, P1+/P0, the classical models) and
// 2.3e-15 (P1+/P1) of Σ ρ_r |Ω_r| = 9.2; tolerance 1e-13.
// And the single-material path: per-cell coefficients that are all equal are the
// uniform coefficient, and give the matrices of a single material bit for bit.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/post/stress.hpp"
#include "cdyn/problems/elastic_contact.hpp"

using namespace cdyn;

namespace {

const Material kSoft{1.3, 1.0, 0.5}, kStiff{7.9, 30.0, 20.0};  // ρ, λ, μ
const double kP = 0.3;                                          // the pressure on the top

// The column [0, 1] × [0, 2], 2n × 2n cells, interior vertices moved along x (so the
// grid has no symmetry, while the interface y = 1 stays a line of edges); regions 0
// "soft" (y < 1) and 1 "stiff".
Mesh column(int n) {
  const int N = 2 * n;
  Mesh m = unit_square_mesh(N, 1.0, 2.0);
  for (int j = 1; j < N; ++j)
    for (int i = 1; i < N; ++i) m.vertices[i + j * (N + 1)].x += 0.2 / N * std::sin(12.9898 * i + 78.233 * j);
  m.region_names = {"soft", "stiff"};
  m.cell_region.resize(m.n_cells());
  for (int c = 0; c < m.n_cells(); ++c) {
    double y = 0.0;
    for (int k = 0; k < 3; ++k) y += m.vertices[m.cells[c][k]].y / 3.0;
    m.cell_region[c] = y < 1.0 ? 0 : 1;
  }
  return m;
}

// The data of a column with the two materials (no contact, nothing fixed).
ElasticContactData two_materials(Element W) {
  ElasticContactData d;
  d.mass = MassSpec::pair(W, Element::P0);
  d.rho = kStiff.rho;
  d.lambda = kStiff.lambda;
  d.mu = kStiff.mu;
  d.region_materials = {{0, kSoft}};  // the stiff region keeps the body's material
  d.obstacle = false;
  return d;
}

// ∫ρ over the column: |Ω_soft| = |Ω_stiff| = 1.
const double kMass = kSoft.rho + kStiff.rho;

}  // namespace

TEST(Materials, CellMaterialsFollowTheRegions) {
  const Mesh mesh = column(2);
  const CellMaterials m = cell_materials(mesh, two_materials(Element::P1));
  ASSERT_FALSE(m.rho.is_uniform());
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const Material& expected = mesh.cell_region[c] == 0 ? kSoft : kStiff;
    EXPECT_EQ(m.rho[c], expected.rho);
    EXPECT_EQ(m.lambda[c], expected.lambda);
    EXPECT_EQ(m.mu[c], expected.mu);
  }
}

TEST(Materials, MassIsTheSumOfDensityTimesArea) {
  const Mesh mesh = column(2);
  const CellCoefficient rho = cell_materials(mesh, two_materials(Element::P1)).rho;
  struct Case {
    Element W;
    const char* spec;
  };
  const Case cases[] = {{Element::P1, "P1/P1"},       {Element::P1, "P1/P0"},       {Element::P1Bubble, "P1+/P0"},
                        {Element::P1Bubble, "P1+/P1"}, {Element::P2, "P2/P1"},       {Element::P2, "P2/P0"},
                        {Element::P1, "consistent"},   {Element::P1, "lumped"},      {Element::P1, "redistributed"}};
  for (const Case& k : cases) {
    const FESpace W(mesh, k.W, 2);
    const DirichletLift bc(W, {});
    // the redistributed mass: both components of the base vertices massless
    std::vector<int> contact;
    for (int v : mesh.part_vertices({mesh.part_index("bottom")}))
      for (int c : {0, 1}) contact.push_back(bc.free_index(W.vertex_dof(v, c)));
    const auto model = make_mass_model(W, bc, k.spec, rho, contact);
    for (int comp : {0, 1}) {
      const Eigen::VectorXd one = W.interpolate(std::vector<Field>{
          [comp](double, double, double) { return comp == 0 ? 1.0 : 0.0; },
          [comp](double, double, double) { return comp == 1 ? 1.0 : 0.0; }});
      // 1ᵀ M 1 = 1ᵀ Bᵀ C⁻¹ B 1 through the model's own operations (no M needed).
      const double m = model->momentum(model->velocity(one)).dot(one);
      EXPECT_NEAR(m, kMass, 1e-13 * kMass) << k.spec << ", component " << comp;
    }
  }
}

TEST(Materials, WeightIsTheSumOfDensityTimesAreaTimesGravity) {
  const Mesh mesh = column(2);
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    ElasticContactData d = two_materials(e);
    d.gravity = {0.4, -9.81};
    const ConstrainedProblem p = build_elastic_contact(mesh, d);
    const Eigen::VectorXd& L = p.full_load(0.0);
    for (int comp : {0, 1}) {
      const Eigen::VectorXd one = p.W->interpolate(std::vector<Field>{
          [comp](double, double, double) { return comp == 0 ? 1.0 : 0.0; },
          [comp](double, double, double) { return comp == 1 ? 1.0 : 0.0; }});
      EXPECT_NEAR(one.dot(L), d.gravity[comp] * kMass, 1e-13 * 9.81 * kMass) << to_string(e);
    }
  }
}

// The oedometer: confined compression of the two layers against the series springs.
TEST(Materials, TwoLayerColumnIsTwoSpringsInSeries) {
  const Mesh mesh = column(2);
  const CellMaterials m = cell_materials(mesh, two_materials(Element::P1));
  const double M_soft = kSoft.lambda + 2 * kSoft.mu, M_stiff = kStiff.lambda + 2 * kStiff.mu;
  auto exact_uy = [&](double y) { return y <= 1.0 ? -kP * y / M_soft : -kP / M_soft - kP * (y - 1.0) / M_stiff; };
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(mesh, e, 2);
    const SparseMatrix A = assemble_elasticity(W, m.lambda, m.mu);
    const int top = mesh.part_index("top");
    const Eigen::VectorXd L = assemble_boundary_load(W, {top}, {[](double, double, double) { return 0.0; },
                                                               [](double, double, double) { return -kP; }});
    // u_x = 0 on the sides and the base, u_y = 0 on the base (dof points on x = 0, 1 or y = 0).
    std::vector<int> index(W.n_dofs(), -1);
    int n = 0;
    for (int s = 0; s < W.n_scalar_dofs(); ++s) {
      const Point& x = W.dof_points()[s];
      const bool side = x.x == 0.0 || x.x == 1.0, base = x.y == 0.0;
      if (!(side || base)) index[W.dof(s, 0)] = n++;
      if (!base) index[W.dof(s, 1)] = n++;
    }
    const SparseMatrix A_ff = submatrix(A, index, n, index, n);
    Eigen::VectorXd L_f(n);
    for (int i = 0; i < W.n_dofs(); ++i)
      if (index[i] >= 0) L_f[index[i]] = L[i];
    const Eigen::SimplicialLDLT<SparseMatrix> solver(A_ff);
    ASSERT_EQ(solver.info(), Eigen::Success);
    const Eigen::VectorXd U_f = solver.solve(L_f);
    Eigen::VectorXd U = Eigen::VectorXd::Zero(W.n_dofs());
    for (int i = 0; i < W.n_dofs(); ++i)
      if (index[i] >= 0) U[i] = U_f[index[i]];

    // The interpolant of the exact solution, dof by dof (bubbles 0: linear on each cell).
    const Eigen::VectorXd exact = W.interpolate(std::vector<Field>{
        [](double, double, double) { return 0.0; }, [&](double, double y, double) { return exact_uy(y); }});
    const double scale = std::abs(exact_uy(2.0));
    EXPECT_LE((U - exact).cwiseAbs().maxCoeff(), 1e-12 * scale) << to_string(e);
    // u_y(top) = −p (h_soft / M_soft + h_stiff / M_stiff)
    for (int v : mesh.part_vertices({top}))
      EXPECT_NEAR(U[W.vertex_dof(v, 1)], -kP * (1.0 / M_soft + 1.0 / M_stiff), 1e-12 * scale) << to_string(e);

    // σ_yy = −p in both layers; σ_xx = σ_zz = −p λ_r / M_r jumps at the interface.
    const std::vector<StressState> cells = cell_stress(W, U, m.lambda, m.mu);
    for (int c = 0; c < mesh.n_cells(); ++c) {
      const Material& r = mesh.cell_region[c] == 0 ? kSoft : kStiff;
      const double M_r = r.lambda + 2 * r.mu;
      EXPECT_NEAR(cells[c].sigma.yy, -kP, 1e-12 * kP) << to_string(e) << " cell " << c;
      EXPECT_NEAR(cells[c].sigma.xx, -kP * r.lambda / M_r, 1e-12 * kP) << to_string(e) << " cell " << c;
      EXPECT_NEAR(cells[c].sigma.zz, -kP * r.lambda / M_r, 1e-12 * kP) << to_string(e) << " cell " << c;
      EXPECT_NEAR(cells[c].sigma.xy, 0.0, 1e-12 * kP) << to_string(e) << " cell " << c;
      EXPECT_NEAR(cells[c].epsilon.yy, -kP / M_r, 1e-12 * kP) << to_string(e) << " cell " << c;
    }
  }
}

// One material given per cell, or per region with the body's own values, is the
// single material: the same matrices and load, bit for bit.
TEST(Materials, OneMaterialEverywhereIsTheSingleMaterialPath) {
  const Mesh mesh = column(2);
  EXPECT_TRUE(CellCoefficient(std::vector<double>(mesh.n_cells(), 2.5)).is_uniform());
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(mesh, e, 2), H(mesh, Element::P0, 2);
    EXPECT_TRUE(same_matrix(assemble_mass(H, W, 2.5), SparseMatrix(2.5 * assemble_mass(H, W))));
    EXPECT_TRUE(same_matrix(assemble_elasticity(W, CellCoefficient(std::vector<double>(mesh.n_cells(), 3.0)), 2.0),
                            assemble_elasticity(W, 3.0, 2.0)));
    for (const char* spec : {"P0", "consistent"}) {
      if (std::string(spec) == "consistent" && e != Element::P1) continue;
      ElasticContactData one;
      one.mass = std::string(spec) == "P0" ? MassSpec::pair(e, Element::P0) : MassSpec::parse(spec, e);
      one.rho = 1.7;
      one.lambda = 3.0;
      one.mu = 2.0;
      one.gravity = {0.0, -9.81};
      one.dirichlet_parts = {mesh.part_index("top")};
      one.contact_parts = {mesh.part_index("bottom")};
      ElasticContactData same = one;
      same.region_materials = {{0, {1.7, 3.0, 2.0}}, {1, {1.7, 3.0, 2.0}}};
      const ConstrainedProblem a = build_elastic_contact(mesh, one), b = build_elastic_contact(mesh, same);
      EXPECT_TRUE(same_matrix(a.A_full, b.A_full));
      EXPECT_TRUE(same_matrix(a.A, b.A));
      EXPECT_TRUE(same_matrix(*a.mass->matrix(), *b.mass->matrix())) << spec;
      EXPECT_TRUE(a.full_load(0.0) == b.full_load(0.0));
    }
  }
}

TEST(Materials, BadRegionsAreInputErrors) {
  const Mesh mesh = column(1);
  ElasticContactData d = two_materials(Element::P1);
  d.region_materials = {{2, kSoft}};
  EXPECT_THROW(cell_materials(mesh, d), InputError);
  d.region_materials = {{0, kSoft}, {0, kStiff}};
  EXPECT_THROW(cell_materials(mesh, d), InputError);
  d.region_materials = {{1, {0.0, 1.0, 1.0}}};
  try {
    cell_materials(mesh, d);
    FAIL() << "a region with ρ = 0 was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.parameter(), "rho");
    EXPECT_NE(e.message().find("stiff"), std::string::npos) << e.message();
  }
  d.region_materials = {{1, {1.0, 1.0, -1.0}}};
  EXPECT_THROW(build_elastic_contact(mesh, d), InputError);
  Mesh no_regions = unit_square_mesh(2);
  d.region_materials = {{0, kSoft}};
  EXPECT_THROW(cell_materials(no_regions, d), InputError);
  // a per-cell coefficient of the wrong length
  const FESpace W(mesh, Element::P1, 2);
  EXPECT_THROW(assemble_elasticity(W, CellCoefficient(std::vector<double>{1.0, 2.0}), 1.0), InputError);
  EXPECT_THROW(assemble_mass(W, W, CellCoefficient(std::vector<double>{1.0, 2.0})), InputError);
}
