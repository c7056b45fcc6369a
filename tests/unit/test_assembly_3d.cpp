// test_assembly_3d.cpp — the matrices A, B, C and L on tetrahedra, against closed forms.
//
//  - the element matrices of the reference tetrahedron: ∫ λ^a = a! 3!/(|a| + 3)! |T|;
//  - 1ᵀB1 = |Ω| for every pair, C of P0 = diag|K|, Σ L_i = ∫ f and Σ L_i = ∫_Γ g;
//  - the kernel of A: the constants (Laplacian), the six rigid motions (elasticity);
//  - A U for an affine u is the boundary flux ∫_∂Ω (∇u·n) φ_i, resp. ∫_∂Ω σn·φ_i: the
//    stiffness and the Neumann load on triangles agree with each other;
//  - patch tests: data of the space's degree are reproduced to round-off.
// Meshes: the Kuhn cube, the same with its interior vertices moved (so that nothing
// holds by the symmetry of the grid), and gmsh's box (data/geo/box.geo).
// Tolerances: exact identities of exactly integrated polynomials, so round-off only;
// each test prints its worst measured value, and the bounds leave 10–100× above it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cdyn/fe/assembly.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/fe/norms.hpp"
#include "cdyn/gmsh_mesh.hpp"

using namespace cdyn;

namespace {

// The Kuhn cube with its interior vertices moved by a fixed pseudo-random amount of at
// most 0.15 h per coordinate (every tetrahedron stays positive: Mesh::check).
Mesh perturbed_cube(int n) {
  Mesh m = unit_cube_mesh(n);
  const double h = 1.0 / n;
  for (int k = 1; k < n; ++k)
    for (int j = 1; j < n; ++j)
      for (int i = 1; i < n; ++i) {
        Point& p = m.vertices[i + (n + 1) * (j + (n + 1) * k)];
        p.x += 0.15 * h * std::sin(12.9898 * i + 78.233 * j + 37.719 * k);
        p.y += 0.15 * h * std::cos(39.3468 * i + 11.135 * j + 83.155 * k);
        p.z += 0.15 * h * std::sin(73.156 * i + 52.235 * j + 9.151 * k);
      }
  m.check("perturbed cube");
  return m;
}

Mesh box() { return read_mesh(std::string(CDYN_SOURCE_DIR) + "/data/geo/box.geo", {{"h", 0.5}}); }

double factorial(int n) { return std::tgamma(n + 1.0); }

struct Pair {
  Element W, H;
};
const Pair kPairs[] = {{Element::P1, Element::P1},       {Element::P1, Element::P0}, {Element::P1Bubble, Element::P0},
                       {Element::P1Bubble, Element::P1}, {Element::P2, Element::P1}, {Element::P2, Element::P0}};
const Element kContinuous[] = {Element::P1, Element::P1Bubble, Element::P2};

const Field one = [](const Point&, double) { return 1.0; };
const Field zero = [](const Point&, double) { return 0.0; };

Eigen::VectorXd eigenvalues(const SparseMatrix& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(A)};
  return eig.eigenvalues();  // ascending
}

// The outward normal of each part of unit_cube_mesh, in the order of its part names
// (front, right, back, left, bottom, top).
const Point kCubeNormals[6] = {{0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, -1}, {0, 0, 1}};

}  // namespace

// One tetrahedron, the reference one: P1 mass |T|/20 (1 + δ_ij), P1 stiffness, the
// bubble's ∫ b = 256 · 3!/7! |T| = 32/105 |T| and ∫ b² = 256² · 2⁴ 3!/11! |T|.
TEST(Assembly3D, ReferenceTetrahedron) {
  Mesh m;
  m.dim = 3;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.cells = {{0, 1, 2, 3}};
  const double T = 1.0 / 6.0;
  const FESpace P1(m, Element::P1), P1b(m, Element::P1Bubble), P0(m, Element::P0);
  const Eigen::MatrixXd M = Eigen::MatrixXd(assemble_mass(P1, P1));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(M(i, j), T / 20.0 * (i == j ? 2.0 : 1.0), 1e-15 * T);
  // ∇λ0 = −(1, 1, 1), ∇λk = e_k: A = |T| ∇λi·∇λj
  Eigen::Matrix4d expected;
  expected << 3, -1, -1, -1, -1, 1, 0, 0, -1, 0, 1, 0, -1, 0, 0, 1;
  EXPECT_LE((Eigen::MatrixXd(assemble_laplace(P1)) - T * expected).norm(), 1e-15);
  const Eigen::MatrixXd Bb = Eigen::MatrixXd(assemble_mass(P0, P1b));
  EXPECT_NEAR(Bb(0, 4), 256.0 * factorial(3) / factorial(7) * T, 1e-16);
  EXPECT_NEAR(Bb(0, 4), 32.0 / 105.0 * T, 1e-16);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(Bb(0, k), T / 4.0, 1e-16);
  EXPECT_NEAR(assemble_mass(P1b, P1b).coeff(4, 4), 256.0 * 256.0 * 16.0 * factorial(3) / factorial(11) * T, 1e-15);
  EXPECT_NEAR(assemble_mass(P0, P0).coeff(0, 0), T, 1e-17);
}

// Σ_j B_ij 1_j = ∫ ψ_i (1_W the coefficients of 1: ones on vertex and edge dofs, zero on
// the bubbles), so 1ᵀB1 = |Ω| per component; C of P0 is diag |K|.
TEST(Assembly3D, BTimesOneIsTheIntegralOfEachVelocityBasisFunction) {
  double worst = 0.0;
  for (const Mesh& m : {perturbed_cube(3), box()})
    for (const Pair& p : kPairs)
      for (int comps : {1, 3}) {
        const FESpace W(m, p.W, comps), H(m, p.H, comps);
        const SparseMatrix B = assemble_mass(H, W);
        const std::vector<Field> ones(comps, one);
        const Eigen::VectorXd lhs = B * W.interpolate(ones), rhs = assemble_load(H, ones);
        worst = std::max(worst, (lhs - rhs).lpNorm<Eigen::Infinity>() / m.measure());
        EXPECT_LE((lhs - rhs).lpNorm<Eigen::Infinity>(), 1e-14 * m.measure())
            << to_string(p.W) << "/" << to_string(p.H) << " comps " << comps;
        EXPECT_NEAR(W.interpolate(ones).dot(B.transpose() * H.interpolate(ones)), comps * m.measure(),
                    1e-13 * m.measure());
      }
  for (const Mesh& m : {perturbed_cube(2), box()}) {
    const FESpace H(m, Element::P0);
    const SparseMatrix C = assemble_mass(H, H);
    EXPECT_EQ(C.nonZeros(), m.n_cells());
    for (int c = 0; c < m.n_cells(); ++c) EXPECT_NEAR(C.coeff(c, c), m.cell_measure(c), 1e-16);
  }
  std::printf("  B 1 = ∫ψ_i: largest difference %.1e |Ω|\n", worst);
}

TEST(Assembly3D, MatricesAreSymmetricAndTheMassPositiveDefinite) {
  const Mesh m = perturbed_cube(2);
  for (Element e : kContinuous) {
    const FESpace W(m, e), V(m, e, 3);
    for (const SparseMatrix& S : {assemble_mass(W, W), assemble_laplace(W), assemble_elasticity(V, 2.0, 1.5)})
      EXPECT_LE((SparseMatrix(S.transpose()) - S).norm(), 1e-15 * S.norm()) << to_string(e);
  }
  for (Element e : {Element::P0, Element::P1, Element::P1Bubble, Element::P2})
    EXPECT_GT(eigenvalues(assemble_mass(FESpace(m, e), FESpace(m, e)))[0], 0.0) << to_string(e);
}

// Ker A: the constants for the Laplacian (one zero eigenvalue), the six rigid motions
// u = a + ω × x for elasticity (six zero eigenvalues, the seventh well above round-off).
TEST(Assembly3D, KernelsAreTheConstantsAndTheRigidMotions) {
  const Mesh m = perturbed_cube(2);
  const std::vector<std::vector<Field>> rigid = {
      {one, zero, zero},
      {zero, one, zero},
      {zero, zero, one},
      {[](const Point& p, double) { return -p.y; }, [](const Point& p, double) { return p.x; }, zero},
      {zero, [](const Point& p, double) { return -p.z; }, [](const Point& p, double) { return p.y; }},
      {[](const Point& p, double) { return p.z; }, zero, [](const Point& p, double) { return -p.x; }}};
  double worst = 0.0;
  for (Element e : kContinuous) {
    const FESpace W(m, e);
    const SparseMatrix L = assemble_laplace(W);
    EXPECT_LE((L * W.interpolate(one)).norm(), 1e-14 * L.norm()) << to_string(e);
    const Eigen::VectorXd el = eigenvalues(L);
    EXPECT_LE(std::abs(el[0]), 1e-13 * el[el.size() - 1]);
    EXPECT_GT(el[1], 1e-4 * el[el.size() - 1]);

    const FESpace V(m, e, 3);
    const SparseMatrix A = assemble_elasticity(V, 3.0, 1.0);
    for (const auto& r : rigid) {
      const double defect = (A * V.interpolate(r)).norm() / A.norm();
      worst = std::max(worst, defect);
      EXPECT_LE(defect, 1e-14) << to_string(e);
    }
    const Eigen::VectorXd ev = eigenvalues(A);
    const double top = ev[ev.size() - 1];
    for (int k = 0; k < 6; ++k) EXPECT_LE(std::abs(ev[k]), 1e-12 * top) << to_string(e);
    EXPECT_GT(ev[6], 1e-5 * top) << to_string(e) << ": kernel larger than the rigid motions";
  }
  std::printf("  rigid motions: largest |A r| / |A| %.1e\n", worst);
}

// An affine u has Δu = 0 and a constant stress, so integration by parts leaves only the
// boundary: (A U)_i = ∫_∂Ω (∇u·n) φ_i ds (Laplacian) and ∫_∂Ω σ n · φ_i ds (elasticity,
// σ = λ tr ε I + 2με), which assemble_boundary_load computes facet by facet on the
// six faces of the cube with their outward normals.
TEST(Assembly3D, AffineFieldsGiveTheBoundaryFlux) {
  const Mesh m = perturbed_cube(3);
  const double a[3] = {0.3, -1.2, 0.7};
  const Field u = [&](const Point& p, double) { return 0.5 + a[0] * p.x + a[1] * p.y + a[2] * p.z; };
  // u_k = c_k + G_kl x_l; σ = λ tr(G) I + μ (G + Gᵀ)
  const double G[3][3] = {{0.2, -0.1, 0.4}, {0.3, -0.5, 0.1}, {-0.2, 0.6, 0.3}};
  const double lambda = 2.0, mu = 0.7;
  double sigma[3][3];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l)
      sigma[k][l] = (k == l ? lambda * (G[0][0] + G[1][1] + G[2][2]) : 0.0) + mu * (G[k][l] + G[l][k]);
  std::vector<Field> uv;
  for (int k = 0; k < 3; ++k)
    uv.push_back([&G, k](const Point& p, double) { return 0.1 * k + G[k][0] * p.x + G[k][1] * p.y + G[k][2] * p.z; });
  double worst = 0.0;
  for (Element e : kContinuous) {
    const FESpace W(m, e), V(m, e, 3);
    Eigen::VectorXd flux = Eigen::VectorXd::Zero(W.n_dofs()), traction = Eigen::VectorXd::Zero(V.n_dofs());
    for (int part = 0; part < 6; ++part) {
      const Point n = kCubeNormals[part];
      const double an = a[0] * n.x + a[1] * n.y + a[2] * n.z;
      flux += assemble_boundary_load(W, {part}, {[an](const Point&, double) { return an; }});
      std::vector<Field> t;
      for (int k = 0; k < 3; ++k) {
        const double tk = sigma[k][0] * n.x + sigma[k][1] * n.y + sigma[k][2] * n.z;
        t.push_back([tk](const Point&, double) { return tk; });
      }
      traction += assemble_boundary_load(V, {part}, t);
    }
    // (relative to the scale of the round-off of the product, ‖A‖ ‖U‖ in the max norms)
    auto difference = [](const SparseMatrix& A, const Eigen::VectorXd& U, const Eigen::VectorXd& b) {
      const double scale = Eigen::MatrixXd(A).cwiseAbs().rowwise().sum().maxCoeff() * U.lpNorm<Eigen::Infinity>();
      return (A * U - b).lpNorm<Eigen::Infinity>() / scale;
    };
    const double d1 = difference(assemble_laplace(W), W.interpolate(u), flux);
    const double d2 = difference(assemble_elasticity(V, lambda, mu), V.interpolate(uv), traction);
    worst = std::max({worst, d1, d2});
    EXPECT_LE(d1, 1e-13) << to_string(e);
    EXPECT_LE(d2, 1e-13) << to_string(e);
  }
  std::printf("  A U = boundary flux for affine u: largest difference %.1e of ‖A‖ ‖U‖\n", worst);
}

// Σ_i L_i = ∫ f and Σ_i L_i = ∫_Γ g where Σ φ_i = 1 (P1, P2): f = xyz (∫ = 1/8 on the
// cube), g = xy on the top face (1/4) and on the box's part "sides" g = 1 (area 5).
TEST(Assembly3D, LoadsIntegrateTheirData) {
  const Mesh cube = perturbed_cube(3), b = box();
  const Field xyz = [](const Point& p, double) { return p.x * p.y * p.z; };
  const Field xy = [](const Point& p, double) { return p.x * p.y; };
  for (Element e : {Element::P1, Element::P2}) {
    const FESpace W(cube, e);
    EXPECT_NEAR(assemble_load(W, xyz).sum(), 0.125, 1e-15) << to_string(e);
    EXPECT_NEAR(assemble_boundary_load(W, {cube.part_index("top")}, {xy}).sum(), 0.25, 1e-15) << to_string(e);
    const FESpace Wb(b, e, 3);
    const Eigen::VectorXd L = assemble_boundary_load(Wb, {b.part_index("sides")}, {zero, one, zero});
    double s[3] = {0, 0, 0};
    for (int i = 0; i < Wb.n_dofs(); ++i) s[i % 3] += L[i];
    EXPECT_NEAR(s[1], 5.0, 1e-13) << to_string(e);
    EXPECT_EQ(s[0], 0.0);
    EXPECT_EQ(s[2], 0.0);
  }
}

// Patch tests: with the exact solution prescribed on the whole boundary, every space
// reproduces affine solutions of −Δu = 0 and of elasticity without body force, and P2
// the quadratic u = x² + yz − 2y² + z with f = −Δu = 2 (round-off: the condition number
// of A_ff times ε, about 1e-14 here).
TEST(Assembly3D, PatchTests) {
  const Mesh m = perturbed_cube(3);
  const std::vector<int> all = {0, 1, 2, 3, 4, 5};
  const Field affine = [](const Point& p, double) { return 0.1 + 0.2 * p.x - 0.3 * p.y + 0.4 * p.z; };
  const Field quadratic = [](const Point& p, double) { return p.x * p.x + p.y * p.z - 2 * p.y * p.y + p.z; };
  const Field two = [](const Point&, double) { return 2.0; };
  const std::vector<Field> uv = {affine, [](const Point& p, double) { return -0.2 + 0.05 * p.x + 0.01 * p.y; },
                                 [](const Point& p, double) { return 0.3 * p.z - 0.1 * p.x; }};
  double worst = 0.0;
  auto solve = [&](const FESpace& W, const SparseMatrix& A, const Eigen::VectorXd& L, const std::vector<Field>& g) {
    const DirichletLift bc(W, all);
    const Eigen::VectorXd UD = bc.lifting(W, g);
    Eigen::SimplicialLDLT<SparseMatrix> solver(bc.restrict(A));
    EXPECT_EQ(solver.info(), Eigen::Success);
    const Eigen::VectorXd error = bc.extend(solver.solve(bc.restrict(Eigen::VectorXd(L - A * UD))), UD) - W.interpolate(g);
    worst = std::max(worst, error.lpNorm<Eigen::Infinity>());
    return error.lpNorm<Eigen::Infinity>();
  };
  for (Element e : kContinuous) {
    const FESpace W(m, e), V(m, e, 3);
    EXPECT_LE(solve(W, assemble_laplace(W), Eigen::VectorXd::Zero(W.n_dofs()), {affine}), 1e-13) << to_string(e);
    EXPECT_LE(solve(V, assemble_elasticity(V, 2.0, 0.7), Eigen::VectorXd::Zero(V.n_dofs()), uv), 1e-13) << to_string(e);
  }
  const FESpace P2(m, Element::P2);
  EXPECT_LE(solve(P2, assemble_laplace(P2), assemble_load(P2, two), {quadratic}), 1e-13);
  // The L² error of an exact interpolant vanishes (the rule of degree 2·2 + 4 = 8 on
  // every tetrahedron); the H¹ error takes a planar gradient and refuses a 3D mesh.
  EXPECT_LE(l2_error(P2, P2.interpolate(quadratic), quadratic), 1e-14);
  const FESpace P1(m, Element::P1);
  EXPECT_GT(l2_error(P1, P1.interpolate(quadratic), quadratic), 1e-3);
  EXPECT_THROW(h1_seminorm_error(P1, P1.interpolate(affine), [](double, double, double) { return std::array<double, 2>{}; }),
               InputError);
  std::printf("  patch tests: largest nodal error %.1e\n", worst);
}
