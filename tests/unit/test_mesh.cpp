// test_mesh.cpp — the built-in structured meshes: counts, measures, orientation,
// boundary parts, and FreeFEM's square(n,n) numbering.
#include <gtest/gtest.h>

#include "cdyn/mesh/cell_geometry.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fe/fe_space.hpp"

using namespace cdyn;

TEST(Mesh, UnitSquareCountsAndParts) {
  const int n = 5;
  const Mesh m = unit_square_mesh(n);
  EXPECT_EQ(m.n_vertices(), (n + 1) * (n + 1));
  EXPECT_EQ(m.n_cells(), 2 * n * n);
  EXPECT_EQ(static_cast<int>(m.boundary.size()), 4 * n);
  EXPECT_NEAR(m.measure(), 1.0, 1e-14);
  for (int c = 0; c < m.n_cells(); ++c) EXPECT_NEAR(m.cell_measure(c), 0.5 / (n * n), 1e-15);
  for (const char* p : {"bottom", "right", "top", "left"}) EXPECT_EQ(m.part_vertices({m.part_index(p)}).size(), n + 1u);
  EXPECT_EQ(m.part_vertices({0, 1, 2, 3}).size(), 4u * n);
  // FreeFEM numbering: vertex i + j(n+1) sits at (i/n, j/n).
  EXPECT_DOUBLE_EQ(m.vertices[2 + 3 * (n + 1)].x, 2.0 / n);
  EXPECT_DOUBLE_EQ(m.vertices[2 + 3 * (n + 1)].y, 3.0 / n);
  // complete_boundary() finds nothing new on a mesh whose boundary is fully tagged.
  Mesh copy = m;
  copy.complete_boundary();
  EXPECT_EQ(copy.boundary.size(), m.boundary.size());
  EXPECT_NO_THROW(m.check("unit square"));
}

TEST(Mesh, CompleteBoundaryFindsTheTopologicalBoundary) {
  Mesh m = unit_square_mesh(4);
  m.boundary.clear();
  m.complete_boundary();
  EXPECT_EQ(m.boundary.size(), 16u);
  for (const auto& f : m.boundary) EXPECT_EQ(f.part, -1);
}

TEST(Mesh, IntervalAndUnknownPart) {
  const Mesh m = interval_mesh(10, 2.0);
  EXPECT_EQ(m.n_vertices(), 11);
  EXPECT_NEAR(m.measure(), 2.0, 1e-14);
  EXPECT_NEAR(m.h_max(), 0.2, 1e-14);
  EXPECT_EQ(m.part_vertices({m.part_index("right")}), std::vector<int>{10});
  EXPECT_THROW(m.part_index("top"), InputError);
  EXPECT_THROW(interval_mesh(0), InputError);
}

TEST(Mesh, CheckRejectsInvertedCells) {
  Mesh m = unit_square_mesh(2);
  std::swap(m.cells[3][1], m.cells[3][2]);
  EXPECT_THROW(m.check("test"), InputError);
}

TEST(FESpace, DofCountsAndVertexDofs) {
  const int n = 4;
  const Mesh m = unit_square_mesh(n);
  const int nv = m.n_vertices(), nc = m.n_cells();
  const int ne = 3 * n * n + 2 * n;  // edges of the split square: Euler nv − ne + nc = 1
  EXPECT_EQ(nv - ne + nc, 1);
  EXPECT_EQ(FESpace(m, Element::P0).n_dofs(), nc);
  EXPECT_EQ(FESpace(m, Element::P1).n_dofs(), nv);
  EXPECT_EQ(FESpace(m, Element::P1Bubble).n_dofs(), nv + nc);
  EXPECT_EQ(FESpace(m, Element::P2).n_dofs(), nv + ne);
  const FESpace V(m, Element::P2, 2);
  EXPECT_EQ(V.n_dofs(), 2 * (nv + ne));
  EXPECT_EQ(V.vertex_dof(7, 1), 15);
  // Boundary dofs of P2 on the bottom: n + 1 vertices and n edge midpoints.
  EXPECT_EQ(FESpace(m, Element::P2).boundary_scalar_dofs({m.part_index("bottom")}).size(), 2u * n + 1);
  // Interpolants reproduce their polynomial spaces exactly: a quadratic in P2, a
  // linear field in P1+ (zero bubble coefficients), at any point of any cell.
  const auto quad = [](double x, double y, double) { return 1 + 2 * x - y + x * y + 3 * y * y; };
  const auto lin = [](double x, double y, double) { return 0.5 - x + 2 * y; };
  const FESpace P2(m, Element::P2), P1b(m, Element::P1Bubble);
  const Eigen::VectorXd U2 = P2.interpolate(quad), Ub = P1b.interpolate(lin);
  for (int c = 0; c < m.n_cells(); ++c) {
    const cdyn::RefPoint xi{0.2, 0.3, 0.0};
    const Point x = CellGeometry(m, c).map(xi);
    EXPECT_NEAR(P2.value_in_cell(U2, c, xi), quad(x.x, x.y, 0), 1e-14);
    EXPECT_NEAR(P1b.value_in_cell(Ub, c, xi), lin(x.x, x.y, 0), 1e-14);
    EXPECT_NEAR(Ub[P1b.cell_dofs(c)[3]], 0.0, 1e-15);
  }
}
