// test_wellposedness_3d.cpp — condition (12) on tetrahedra: the membrane-like problem on
// the unit cube (u fixed on the six faces, the obstacle u(a_i) ≥ g at every free
// vertex), each pair's verdict, and the sparse method against the dense reference.
//
// Expected verdicts, by counting and by the seed's argument: P1/P1 and the classical
// masses have Ker B = {0} (β = 0); P1/P0 has N_H = 6n³ cells ≥ N_W = (n − 1)³ and B of
// full column rank, so Ker B = {0} too; the pairs with more displacement than velocity
// dofs away from the vertices — P1+/P0 (one bubble per cell), P1+/P1, P2/P1 (one dof per
// edge) — satisfy (12), as on triangles.  β itself is measured (printed: for n = 2, 3, 4
// P1+/P0 0.241, 0.169, 0.147; P1+/P1 0.154, 0.141, 0.125; P2/P1 1, 0.971, 0.932); the
// two methods agree to 1e-8 relative as in test_wellposedness_sparse.cpp (measured
// 3.0e-15 here).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/wellposedness/condition12.hpp"

using namespace cdyn;

namespace {

WellPosednessSetup clamped_cube_setup(const Mesh& m) {
  WellPosednessSetup setup;
  for (const char* p : {"front", "right", "back", "left", "bottom", "top"}) setup.dirichlet_parts.push_back(m.part_index(p));
  for (int v = 0; v < m.n_vertices(); ++v) setup.constrained_vertices.push_back(v);
  return setup;
}

}  // namespace

TEST(Wellposedness3D, PairsOnTheUnitCube) {
  double worst = 0.0;
  for (int n : {2, 3, 4}) {
    const Mesh mesh = unit_cube_mesh(n);
    WellPosednessSetup setup = clamped_cube_setup(mesh);
    const int interior = (n - 1) * (n - 1) * (n - 1);
    for (const auto& [spec, satisfied] : std::vector<std::pair<std::string, bool>>{{"P1/P1", false},
                                                                                 {"P1/P0", false},
                                                                                 {"P1+/P0", true},
                                                                                 {"P1+/P1", true},
                                                                                 {"P2/P1", true},
                                                                                 {"consistent", false},
                                                                                 {"lumped", false}}) {
      setup.method = Condition12Method::dense;
      const WellPosedness d = condition12_on(mesh, MassSpec::parse(spec, Element::P1), setup);
      setup.method = Condition12Method::sparse;
      const WellPosedness s = condition12_on(mesh, MassSpec::parse(spec, Element::P1), setup);
      std::printf("  unit cube n = %d  %-10s N_W %5d N_H %5d dim Ker B %5d N_g %4d  beta dense %.6e sparse %.6e\n", n,
                  spec.c_str(), d.n_W, d.n_H, d.dim_ker_B, d.n_g, d.beta, s.beta);
      EXPECT_EQ(d.n_g, interior) << spec;
      EXPECT_EQ(d.satisfied, satisfied) << spec << " n = " << n;
      EXPECT_EQ(s.satisfied, satisfied) << spec << " n = " << n;
      EXPECT_EQ(s.dim_ker_B, d.dim_ker_B) << spec;
      if (satisfied) {
        worst = std::max(worst, std::abs(s.beta - d.beta) / d.beta);
        EXPECT_LE(std::abs(s.beta - d.beta), 1e-8 * d.beta) << spec << " n = " << n;
      }
    }
    // Redistribution needs non-contact free vertices to carry the mass: with the obstacle
    // at every vertex there are none (as on triangles).
    EXPECT_THROW(condition12_on(mesh, MassSpec::parse("redistributed", Element::P1), setup), InputError);
  }
  std::printf("  sparse against dense: %.1e relative\n", worst);
}

// Three components: the constraint rows are n·u at the contact vertices (n_z included),
// and on the cube held at its top face with Γ_C its bottom face, the pairs decide as in
// plane strain: P1+/P0 satisfies (12), P1/P1 does not (Ker B = {0}).
TEST(Wellposedness3D, ThreeComponentsOnAContactFace) {
  const Mesh mesh = unit_cube_mesh(2);
  const FESpace W(mesh, Element::P1, 3);
  const DirichletLift bc(W, {mesh.part_index("top")});
  const std::vector<int> bottom = mesh.part_vertices({mesh.part_index("bottom")});
  const SparseMatrix G = vertex_constraint_matrix(W, bc, bottom, Point{0.6, 0.0, -0.8});
  ASSERT_EQ(G.rows(), static_cast<int>(bottom.size()));
  for (std::size_t r = 0; r < bottom.size(); ++r) {
    EXPECT_EQ(G.coeff(r, bc.free_index(W.vertex_dof(bottom[r], 0))), 0.6);
    EXPECT_EQ(G.coeff(r, bc.free_index(W.vertex_dof(bottom[r], 2))), -0.8);
  }
  EXPECT_EQ(G.nonZeros(), 2 * G.rows());  // no y entry
  WellPosednessSetup setup;
  setup.dirichlet_parts = {mesh.part_index("top")};
  setup.constrained_vertices = bottom;
  setup.components = 3;
  setup.normal = Point{0.0, 0.0, -1.0};
  const WellPosedness p = condition12_on(mesh, MassSpec::parse("P1+/P0"), setup);
  const WellPosedness q = condition12_on(mesh, MassSpec::parse("P1/P1"), setup);
  std::printf("  three components, Γ_C the bottom face: P1+/P0 beta %.4f, P1/P1 beta %.4f\n", p.beta, q.beta);
  EXPECT_EQ(p.n_g, 9);
  EXPECT_TRUE(p.satisfied);
  EXPECT_FALSE(q.satisfied);
}
