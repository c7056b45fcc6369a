// test_assembly.cpp — identities the matrices A, B, C and L must satisfy.
//
// Tolerances: these are exact identities of exactly integrated polynomials, so they
// hold to round-off; 1e-13 relative to the matrix/vector scale leaves a margin of
// ~100 ulps for the sums over cells.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <limits>

#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/fe/quadrature.hpp"

using namespace cdyn;

namespace {

// The structured square with its interior vertices moved by a fixed pseudo-random
// amount (at most 0.25 h), so that no identity holds by symmetry of the grid alone.
Mesh perturbed_square(int n) {
  Mesh m = unit_square_mesh(n);
  const double h = 1.0 / n;
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) {
      Point& p = m.vertices[i + j * (n + 1)];
      p.x += 0.25 * h * std::sin(12.9898 * i + 78.233 * j);
      p.y += 0.25 * h * std::cos(39.3468 * i + 11.135 * j);
    }
  return m;
}

double sym_defect(const SparseMatrix& A) {
  const SparseMatrix D = SparseMatrix(A.transpose()) - A;
  return D.norm() / A.norm();
}

Eigen::VectorXd eigenvalues(const SparseMatrix& A) {
  const Eigen::MatrixXd dense(A);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense);
  return eig.eigenvalues();  // ascending
}

struct Pair {
  Element W, H;
};
const Pair kPairs[] = {{Element::P1, Element::P1},       {Element::P1, Element::P0}, {Element::P1Bubble, Element::P0},
                       {Element::P1Bubble, Element::P1}, {Element::P2, Element::P1}, {Element::P2, Element::P0}};

const Field one = [](double, double, double) { return 1.0; };

}  // namespace

TEST(Assembly, P1MassSumsToTheArea) {
  for (const Mesh& m : {unit_square_mesh(7, 2.0, 3.0), perturbed_square(9), interval_mesh(13, 2.5)}) {
    const FESpace W(m, Element::P1);
    const SparseMatrix C = assemble_mass(W, W);
    EXPECT_NEAR(C.sum(), m.measure(), 1e-13 * m.measure());
  }
  EXPECT_NEAR(unit_square_mesh(7, 2.0, 3.0).measure(), 6.0, 1e-13);
  EXPECT_NEAR(perturbed_square(9).measure(), 1.0, 1e-13);
}

TEST(Assembly, BTimesOneIsTheIntegralOfEachVelocityBasisFunction) {
  // Σ_j B_ij 1_j = ∫ ψ_i · 1, with 1_W the coefficients of the constant function 1 in
  // W^h (ones on vertex/edge dofs, zero on the hierarchical bubbles).
  for (const Mesh& m : {perturbed_square(6), interval_mesh(9, 2.0)})
    for (const Pair& p : kPairs)
      for (int comps : {1, 2}) {
        if (comps == 2 && m.dim == 1) continue;
        const FESpace W(m, p.W, comps), H(m, p.H, comps);
        const SparseMatrix B = assemble_mass(H, W);
        ASSERT_EQ(B.rows(), H.n_dofs());
        ASSERT_EQ(B.cols(), W.n_dofs());
        const std::vector<Field> ones(comps, one);
        const Eigen::VectorXd lhs = B * W.interpolate(ones);
        const Eigen::VectorXd rhs = assemble_load(H, ones);
        EXPECT_LE((lhs - rhs).lpNorm<Eigen::Infinity>(), 1e-14 * m.measure())
            << to_string(p.W) << "/" << to_string(p.H) << " dim " << m.dim << " comps " << comps;
        EXPECT_NEAR(rhs.sum(), comps * m.measure(), 1e-13);
      }
}

TEST(Assembly, P0MassIsTheDiagonalOfCellMeasures) {
  const Mesh m = perturbed_square(5);
  const FESpace H(m, Element::P0);
  const SparseMatrix C = assemble_mass(H, H);
  EXPECT_EQ(C.nonZeros(), m.n_cells());
  for (int c = 0; c < m.n_cells(); ++c) EXPECT_NEAR(C.coeff(c, c), m.cell_measure(c), 1e-16);
}

TEST(Assembly, ReferenceTriangleP1Stiffness) {
  Mesh m;
  m.vertices = {{0, 0}, {1, 0}, {0, 1}};
  m.cells = {{0, 1, 2}};
  const FESpace W(m, Element::P1);
  const Eigen::MatrixXd A = Eigen::MatrixXd(assemble_laplace(W));
  Eigen::Matrix3d expected;
  expected << 1.0, -0.5, -0.5, -0.5, 0.5, 0.0, -0.5, 0.0, 0.5;
  EXPECT_LE((A - expected).norm(), 1e-15);
  // The bubble mass: ∫_T (27λ0λ1λ2)² = 729 · 2|T| · 2!2!2!/8! = 81/560 on |T| = 1/2.
  const FESpace Wb(m, Element::P1Bubble);
  EXPECT_NEAR(assemble_mass(Wb, Wb).coeff(3, 3), 729.0 * 8.0 / 40320.0, 1e-15);
}

TEST(Assembly, TheBubbleIsOrthogonalToP1InEnergy) {
  // ∫_K ∇b = ∮_∂K b n = 0 since b = 27λ0λ1λ2 vanishes on ∂K, so with ∇φ_i constant
  // ∫_K ∇φ_i·∇b = 0: A couples no vertex with a bubble, and fe/assembly.cpp does not store
  // those entries.  The premise, on the reference cell (∫_K ∇b = |det J| J⁻ᵀ ∫ ∇̂b̂, so
  // zero there is zero on every cell), with a rule exact for ∇b (degree 2):
  const QuadratureRule q = cell_quadrature(2, 4);
  double integral[2] = {0.0, 0.0}, size = 0.0;
  for (int p = 0; p < q.size(); ++p) {
    std::array<double, 3> g[4];
    shape_gradients(Element::P1Bubble, 2, q.points[p], g);
    for (int k = 0; k < 2; ++k) integral[k] += q.weights[p] * g[3][k];
    size += q.weights[p] * std::hypot(g[3][0], g[3][1]);
  }
  EXPECT_LE(std::hypot(integral[0], integral[1]), 1e-15 * size);
  // The consequences on a perturbed mesh: P1+'s A is P1's A plus one diagonal entry
  // (block, for elasticity) per bubble, the vertex block equal to P1's to round-off.
  // (test_reference_matrices compares tr(A⁻¹M) with FreeFEM's P1b, which stores the
  // coupling: 1e-10.)
  const Mesh m = perturbed_square(5);
  const int cells = m.n_cells(), nv = m.n_vertices();
  for (int components : {1, 2}) {
    const FESpace P1(m, Element::P1, components), P1b(m, Element::P1Bubble, components);
    const SparseMatrix A1 = components == 1 ? assemble_laplace(P1) : assemble_elasticity(P1, 3.0, 1.0);
    const SparseMatrix Ab = components == 1 ? assemble_laplace(P1b) : assemble_elasticity(P1b, 3.0, 1.0);
    EXPECT_EQ(Ab.nonZeros(), A1.nonZeros() + cells * components * components) << components;
    const int n1 = nv * components;  // vertex dofs first (fe/fe_space.hpp)
    const double defect = (Eigen::MatrixXd(Ab).topLeftCorner(n1, n1) - Eigen::MatrixXd(A1)).norm();
    EXPECT_LE(defect, 1e-14 * A1.norm()) << components;
  }
}

TEST(Assembly, MassAndStiffnessAreSymmetric) {
  const Mesh m = perturbed_square(5);
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(m, e), V(m, e, 2);
    EXPECT_LE(sym_defect(assemble_mass(W, W)), 1e-15) << to_string(e);
    EXPECT_LE(sym_defect(assemble_laplace(W)), 1e-15) << to_string(e);
    EXPECT_LE(sym_defect(assemble_elasticity(V, 2.0, 1.5)), 1e-15) << to_string(e);
  }
}

TEST(Assembly, MassIsPositiveDefinite) {
  const Mesh m = perturbed_square(3);
  for (Element e : {Element::P0, Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(m, e);
    EXPECT_GT(eigenvalues(assemble_mass(W, W))[0], 0.0) << to_string(e);
  }
}

TEST(Assembly, NeumannLaplacianKernelIsTheConstants) {
  for (const Mesh& m : {perturbed_square(3), interval_mesh(6)})
    for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
      const FESpace W(m, e);
      const SparseMatrix A = assemble_laplace(W);
      EXPECT_LE((A * W.interpolate(one)).norm(), 1e-13 * A.norm()) << to_string(e);
      const Eigen::VectorXd ev = eigenvalues(A);
      EXPECT_LE(std::abs(ev[0]), 1e-12 * ev[ev.size() - 1]) << to_string(e);
      EXPECT_GT(ev[1], 1e-4 * ev[ev.size() - 1]) << to_string(e) << ": kernel larger than the constants";
    }
}

TEST(Assembly, ElasticityKernelIsTheRigidMotions) {
  const Mesh m = perturbed_square(3);
  const std::vector<std::vector<Field>> rigid = {
      {one, [](double, double, double) { return 0.0; }},
      {[](double, double, double) { return 0.0; }, one},
      {[](double, double y, double) { return -y; }, [](double x, double, double) { return x; }}};
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(m, e, 2);
    const SparseMatrix A = assemble_elasticity(W, 3.0, 1.0);
    for (const auto& r : rigid) EXPECT_LE((A * W.interpolate(r)).norm(), 1e-13 * A.norm()) << to_string(e);
    const Eigen::VectorXd ev = eigenvalues(A);
    const double top = ev[ev.size() - 1];
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(ev[k]), 1e-12 * top) << to_string(e);
    EXPECT_GT(ev[3], 1e-5 * top) << to_string(e) << ": kernel larger than the rigid motions";
  }
}

TEST(Assembly, ElasticityPassesThePatchTest) {
  // A linear displacement with zero body force is an exact solution of plane-strain
  // elasticity; prescribed on the whole boundary, every space containing P1 must
  // reproduce it to round-off (condition number × ε ≈ 1e-12 here).
  const Mesh m = perturbed_square(6);
  const std::vector<Field> u = {[](double x, double y, double) { return 0.1 + 0.02 * x - 0.03 * y; },
                                [](double x, double y, double) { return -0.2 + 0.05 * x + 0.01 * y; }};
  std::vector<int> all_parts = {0, 1, 2, 3};
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(m, e, 2);
    const SparseMatrix A = assemble_elasticity(W, 2.0, 0.7);
    const DirichletLift bc(W, all_parts);
    const Eigen::VectorXd UD = bc.lifting(W, u);
    Eigen::SimplicialLDLT<SparseMatrix> solver(bc.restrict(A));
    ASSERT_EQ(solver.info(), Eigen::Success);
    const Eigen::VectorXd U = bc.extend(solver.solve(bc.restrict(Eigen::VectorXd(-(A * UD)))), UD);
    EXPECT_LE((U - W.interpolate(u)).lpNorm<Eigen::Infinity>(), 1e-12) << to_string(e);
  }
}

namespace {
// The chatter's load −0.6 + 3 sin(60 t) as a callable that counts its calls.
auto counted_chatter_load(int& calls) {
  return [&calls](const Point&, double t) {
    ++calls;
    return -0.6 + 3.0 * std::sin(60.0 * t);
  };
}
}  // namespace

TEST(Assembly, ALoadUniformInSpaceIsACombinationOfUnitLoads) {
  // load_in_time: for f uniform in space and depending on t, L(t) = Σ_k f_k(t) ∫ φ_{i,k}
  // from integrals assembled once — linearity of the load in f, the same quadrature, so
  // it equals assemble_load to round-off (asserted 4 ε relative: a sum of the same
  // products in another order) at any t, for every element and both components, each
  // call evaluating each f_k once; a field that varies in space, or a load constant in
  // t, is assembled as before (bit for bit).
  const Mesh mesh = unit_square_mesh(5);
  int calls = 0;
  const auto g = counted_chatter_load(calls);
  auto h = [](const Point&, double t) { return 2.0 - t; };
  const Field gu = Field(g).uniform_in_space(), hu = Field(h).uniform_in_space();
  const Field varying([](const Point& p, double t) { return p.x * p.y + t; });
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(mesh, e, 2);
    const auto L = load_in_time(W, {gu, hu}, true);
    for (double t : {0.0, 0.013, 0.4}) {
      const Eigen::VectorXd assembled = assemble_load(W, {gu, hu}, t);
      calls = 0;
      const Eigen::VectorXd combined = L(t);
      EXPECT_EQ(calls, 1) << to_string(e);
      EXPECT_LE((combined - assembled).lpNorm<Eigen::Infinity>(),
                4 * std::numeric_limits<double>::epsilon() * assembled.lpNorm<Eigen::Infinity>())
          << to_string(e) << " t = " << t;
      EXPECT_EQ(load_in_time(W, {varying, hu}, true)(t), assemble_load(W, {varying, hu}, t)) << to_string(e);
      EXPECT_EQ(load_in_time(W, {gu, hu}, false)(t), assembled) << to_string(e);
    }
  }
}

TEST(Assembly, AUniformFieldIsIntegratedFromOneEvaluation) {
  // A field marked uniform in space (an expression without x, y, z) is evaluated once
  // per time; the load is the same sum of the same products, so the vectors agree bit
  // for bit with those of the unmarked field, and the field is called once, not at
  // every quadrature point.
  const Mesh mesh = unit_square_mesh(4);
  int calls = 0;
  const auto f = counted_chatter_load(calls);
  const Field varying(f);
  const Field uniform = Field(f).uniform_in_space();
  EXPECT_TRUE(varying.depends_on_space());
  EXPECT_FALSE(uniform.depends_on_space());
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(mesh, e, 2);
    calls = 0;
    const Eigen::VectorXd a = assemble_load(W, {varying, uniform}, 0.3);
    const int calls_varying = calls;
    calls = 0;
    const Eigen::VectorXd b = assemble_load(W, {uniform, uniform}, 0.3);
    EXPECT_EQ(calls, 2);  // once per component
    EXPECT_GT(calls_varying, mesh.n_cells());
    // component x of a (varying) equals component x of b (uniform), exactly
    for (int s = 0; s < W.n_scalar_dofs(); ++s) EXPECT_EQ(a[W.dof(s, 0)], b[W.dof(s, 0)]) << to_string(e);
    const std::vector<int> all{0, 1, 2, 3};
    calls = 0;
    const Eigen::VectorXd ga = assemble_boundary_load(W, all, {varying, varying}, 0.3);
    calls = 0;
    const Eigen::VectorXd gb = assemble_boundary_load(W, all, {uniform, uniform}, 0.3);
    EXPECT_EQ(calls, 2);
    EXPECT_EQ(ga, gb) << to_string(e);
  }
}
