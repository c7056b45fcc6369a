// test_stress.cpp — strain, stress and von Mises stress of post/stress.hpp.
//
// The exact check: an affine displacement u(x) = u₀ + G x has the constant strain
// ε = ½(G + Gᵀ), which P1, P1+ and P2 all represent exactly (the interpolant of an
// affine field is the field: nodal values for P1 and P2, bubble coefficient 0 for the
// hierarchical P1+).  So in every cell and at every vertex ε, σ = λ tr ε I + 2μ ε and
// σ_vM must be those constants to round-off — also with λ, μ differing from cell to
// cell, where σ is the constant of the cell's own material.  Meshes: the unit square
// with its interior vertices moved (no identity by symmetry of the grid alone).
// Tolerance 1e-13 relative: ∇u_h is a sum of a few products per cell (measured on the
// 158 cells of the disk at lc = 5: σ to 1.8e-15 (P1), 1.6e-15 (P1+), 4.4e-15 (P2) of
// λ + 2μ in the cells, ≤ 1.1e-15 at the vertices).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/fe_space.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/post/stress.hpp"

using namespace cdyn;

namespace {

// An unstructured mesh (no identity by symmetry of a grid): the disk of radius 20 of
// data/geo/disk.geo with the mesh size lc.
Mesh disk(double lc) { return read_mesh(std::string(CDYN_SOURCE_DIR) + "/data/geo/disk.geo", {{"lc", lc}}); }

// u = u₀ + G x with G = [[g00, g01], [g10, g11]].
constexpr double g00 = 0.3, g01 = -0.7, g10 = 0.2, g11 = -0.45;
const std::vector<Field> affine = {[](double x, double y, double) { return 0.1 + g00 * x + g01 * y; },
                                   [](double x, double y, double) { return -0.2 + g10 * x + g11 * y; }};
const SymmetricTensor exact_epsilon{g00, g11, 0.0, 0.5 * (g01 + g10)};

// σ_vM as (3/2 s:s)^½ with s the deviator of the full 3 × 3 tensor: an independent
// form of the formula post/stress.hpp uses.
double von_mises_from_deviator(const SymmetricTensor& t) {
  Eigen::Matrix3d s;
  s << t.xx, t.xy, 0.0, t.xy, t.yy, 0.0, 0.0, 0.0, t.zz;
  const Eigen::Matrix3d dev = s - s.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * (dev.array() * dev.array()).sum());
}

void expect_tensor(const SymmetricTensor& a, const SymmetricTensor& b, double scale, const std::string& what) {
  const double tol = 1e-13 * scale;
  EXPECT_NEAR(a.xx, b.xx, tol) << what;
  EXPECT_NEAR(a.yy, b.yy, tol) << what;
  EXPECT_NEAR(a.zz, b.zz, tol) << what;
  EXPECT_NEAR(a.xy, b.xy, tol) << what;
}

}  // namespace

TEST(Stress, PlaneStrainLawAndVonMises) {
  const double lambda = 1.7, mu = 0.6;
  const SymmetricTensor s = isotropic_stress(exact_epsilon, lambda, mu);
  const double tr = g00 + g11;
  EXPECT_DOUBLE_EQ(s.xx, lambda * tr + 2 * mu * g00);
  EXPECT_DOUBLE_EQ(s.yy, lambda * tr + 2 * mu * g11);
  EXPECT_DOUBLE_EQ(s.xy, mu * (g01 + g10));
  // σ_zz = λ tr ε = ν (σ_xx + σ_yy), ν = λ / (2(λ + μ)): plane strain, not plane stress.
  EXPECT_DOUBLE_EQ(s.zz, lambda * tr);
  EXPECT_NEAR(s.zz, lambda / (2 * (lambda + mu)) * (s.xx + s.yy), 1e-15);
  EXPECT_NEAR(von_mises(s), von_mises_from_deviator(s), 1e-15 * von_mises(s));
  // Pure pressure has no von Mises stress; uniaxial stress σ has σ_vM = |σ|.
  EXPECT_EQ(von_mises({-2.0, -2.0, -2.0, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(von_mises({3.0, 0.0, 0.0, 0.0}), 3.0);
  EXPECT_DOUBLE_EQ(von_mises({0.0, 0.0, 0.0, 1.0}), std::sqrt(3.0));  // pure shear τ: √3 τ
}

TEST(Stress, AffineDisplacementGivesTheExactStressInEveryCell) {
  const Mesh mesh = disk(5.0);
  // Two materials, cells alternating with their index, and one uniform.
  std::vector<double> lambda(mesh.n_cells()), mu(mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) {
    lambda[c] = c % 3 == 0 ? 1.5 : 40.0;
    mu[c] = c % 3 == 0 ? 0.8 : 12.0;
  }
  const CellCoefficient per_cell_lambda(lambda), per_cell_mu(mu);
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(mesh, e, 2);
    const Eigen::VectorXd U = W.interpolate(affine);
    for (bool uniform : {true, false}) {
      const std::vector<StressState> cells = uniform ? cell_stress(W, U, 2.0, 0.5)
                                                     : cell_stress(W, U, per_cell_lambda, per_cell_mu);
      ASSERT_EQ(static_cast<int>(cells.size()), mesh.n_cells());
      for (int c = 0; c < mesh.n_cells(); ++c) {
        const double l = uniform ? 2.0 : lambda[c], m = uniform ? 0.5 : mu[c];
        const SymmetricTensor sigma = isotropic_stress(exact_epsilon, l, m);
        const std::string what = to_string(e) + (uniform ? " uniform" : " two materials") + ", cell " + std::to_string(c);
        expect_tensor(cells[c].epsilon, exact_epsilon, 1.0, what);
        expect_tensor(cells[c].sigma, sigma, l + 2 * m, what);
        EXPECT_NEAR(cells[c].von_mises, von_mises_from_deviator(sigma), 1e-13 * (l + 2 * m)) << what;
      }
      if (!uniform) continue;
      // The vertex average of a constant is the constant.
      const std::vector<StressState> at = vertex_stress(mesh, cells);
      ASSERT_EQ(static_cast<int>(at.size()), mesh.n_vertices());
      const SymmetricTensor sigma = isotropic_stress(exact_epsilon, 2.0, 0.5);
      for (int v = 0; v < mesh.n_vertices(); ++v) {
        expect_tensor(at[v].epsilon, exact_epsilon, 1.0, to_string(e) + " vertex " + std::to_string(v));
        expect_tensor(at[v].sigma, sigma, 3.0, to_string(e) + " vertex " + std::to_string(v));
      }
    }
  }
}

// ε(u_h) is affine on a cell for P2: the cell value is its mean, the value at the
// centroid.  u = (x², x y) is in P2, ε = [[2x, y/2], [y/2, x]].
TEST(Stress, P2CellValueIsTheMeanOverTheCell) {
  const Mesh mesh = disk(10.0);
  const FESpace W(mesh, Element::P2, 2);
  const Eigen::VectorXd U = W.interpolate(std::vector<Field>{[](double x, double, double) { return x * x; },
                                                             [](double x, double y, double) { return x * y; }});
  const std::vector<StressState> cells = cell_stress(W, U, 1.0, 1.0);
  for (int c = 0; c < mesh.n_cells(); ++c) {
    double xc = 0, yc = 0;
    for (int k = 0; k < 3; ++k) {
      xc += mesh.vertices[mesh.cells[c][k]].x / 3;
      yc += mesh.vertices[mesh.cells[c][k]].y / 3;
    }
    expect_tensor(cells[c].epsilon, {2 * xc, xc, 0.0, 0.5 * yc}, 100.0, "cell " + std::to_string(c));  // |x| ≤ 41
  }
}

// The bubble's gradient has zero mean on its cell (∫_K ∇b = ∮_∂K b ν = 0): a field that
// is only bubbles has zero cell strain, and P1+ cell values are those of its P1 part.
TEST(Stress, TheP1BubbleHasNoMeanStrain) {
  const Mesh mesh = disk(10.0);
  const FESpace W(mesh, Element::P1Bubble, 2);
  Eigen::VectorXd U = W.interpolate(affine);
  for (int c = 0; c < mesh.n_cells(); ++c)  // the bubble dofs follow the vertex dofs
    for (int k = 0; k < 2; ++k) U[W.dof(W.cell_dofs(c)[3], k)] = std::sin(3.0 * c + k);
  for (const StressState& s : cell_stress(W, U, 2.0, 0.5)) expect_tensor(s.epsilon, exact_epsilon, 1.0, "P1+");
}

TEST(Stress, BadInputIsAnInputError) {
  const Mesh mesh = unit_square_mesh(2);
  const FESpace W(mesh, Element::P1, 2), scalar(mesh, Element::P1, 1);
  EXPECT_THROW(cell_stress(scalar, Eigen::VectorXd::Zero(scalar.n_dofs()), 1.0, 1.0), InputError);
  EXPECT_THROW(cell_stress(W, Eigen::VectorXd::Zero(3), 1.0, 1.0), InputError);
  EXPECT_THROW(cell_stress(W, Eigen::VectorXd::Zero(W.n_dofs()), CellCoefficient(std::vector<double>{1.0, 2.0}), 1.0),
               InputError);
  EXPECT_THROW(vertex_stress(mesh, {}), InputError);
}
