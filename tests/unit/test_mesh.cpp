// test_mesh.cpp — the built-in structured meshes: counts, measures, orientation,
// boundary parts, and FreeFEM's square(n,n) numbering.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "cdyn/mesh/cell_geometry.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fe/fe_space.hpp"

using namespace cdyn;

namespace {

// P2 reproduces the quadratic `quad` and P1+ the affine `lin` with zero bubble
// coefficients, at the reference point xi of every cell.
void expect_exact_interpolants(const Mesh& m, const Field& quad, const Field& lin, const RefPoint& xi) {
  const FESpace P2(m, Element::P2), P1b(m, Element::P1Bubble);
  const Eigen::VectorXd U2 = P2.interpolate(quad), Ub = P1b.interpolate(lin);
  for (int c = 0; c < m.n_cells(); ++c) {
    const Point x = CellGeometry(m, c).map(xi);
    EXPECT_NEAR(P2.value_in_cell(U2, c, xi), quad(x, 0.0), 1e-14);
    EXPECT_NEAR(P1b.value_in_cell(Ub, c, xi), lin(x, 0.0), 1e-14);
    EXPECT_NEAR(Ub[P1b.cell_dofs(c)[m.dim + 1]], 0.0, 1e-15);
  }
}

}  // namespace

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
  Mesh m = unit_square_mesh(2), cube = unit_cube_mesh(1);
  std::swap(m.cells[3][1], m.cells[3][2]);
  std::swap(cube.cells[4][2], cube.cells[4][3]);
  EXPECT_THROW(m.check("test"), InputError);
  EXPECT_THROW(cube.check("test"), InputError);
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
  // Interpolants reproduce their polynomial spaces exactly.
  expect_exact_interpolants(m, [](double x, double y, double) { return 1 + 2 * x - y + x * y + 3 * y * y; },
                            [](double x, double y, double) { return 0.5 - x + 2 * y; }, {0.2, 0.3, 0.0});
}

// The unit cube split into 6n³ Kuhn tetrahedra: counts, volumes, the six parts, the
// outward orientation of the boundary triangles, and conformity — every interior
// triangle is shared by exactly two tetrahedra (complete_boundary finds no untagged
// facet) and Euler's formula for a ball, V − E + F − T = 1, holds.
TEST(Mesh, UnitCubeIsAConformingKuhnSplit) {
  const int n = 3;
  const Mesh m = unit_cube_mesh(n);
  ASSERT_EQ(m.dim, 3);
  EXPECT_EQ(m.n_vertices(), (n + 1) * (n + 1) * (n + 1));
  EXPECT_EQ(m.n_cells(), 6 * n * n * n);
  EXPECT_EQ(static_cast<int>(m.boundary.size()), 12 * n * n);
  EXPECT_NO_THROW(m.check("unit cube"));
  for (int c = 0; c < m.n_cells(); ++c) EXPECT_NEAR(m.cell_measure(c), 1.0 / (6 * n * n * n), 1e-17);
  EXPECT_NEAR(m.measure(), 1.0, 1e-14);
  EXPECT_NEAR(m.h_max(), std::sqrt(3.0) / n, 1e-15);
  // vertex i + (n+1)(j + (n+1)k) at (i, j, k)/n
  const Point& p = m.vertices[1 + (n + 1) * (2 + (n + 1) * 3)];
  EXPECT_DOUBLE_EQ(p.x, 1.0 / n);
  EXPECT_DOUBLE_EQ(p.y, 2.0 / n);
  EXPECT_DOUBLE_EQ(p.z, 1.0);

  // The parts: name, the coordinate that is fixed on it, its value, the outward normal.
  const struct {
    const char* name;
    int axis;
    double value;
  } parts[] = {{"front", 1, 0.0}, {"right", 0, 1.0}, {"back", 1, 1.0},
               {"left", 0, 0.0},  {"bottom", 2, 0.0}, {"top", 2, 1.0}};
  EXPECT_EQ(m.part_names, (std::vector<std::string>{"front", "right", "back", "left", "bottom", "top"}));
  auto coordinate = [](const Point& q, int axis) { return axis == 0 ? q.x : axis == 1 ? q.y : q.z; };
  for (const auto& part : parts) {
    const int index = m.part_index(part.name);
    EXPECT_EQ(m.part_vertices({index}).size(), static_cast<std::size_t>((n + 1) * (n + 1))) << part.name;
    double area = 0.0;
    for (const auto& f : m.boundary) {
      if (f.part != index) continue;
      const Point &a = m.vertices[f.vertices[0]], &b = m.vertices[f.vertices[1]], &c = m.vertices[f.vertices[2]];
      for (const Point* q : {&a, &b, &c}) EXPECT_EQ(coordinate(*q, part.axis), part.value) << part.name;
      // (b − a) × (c − a): its component along the axis is twice the signed area
      const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, w[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
      const double normal[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const double outward = part.value == 0.0 ? -1.0 : 1.0;
      EXPECT_NEAR(outward * normal[part.axis], 1.0 / (n * n), 1e-15) << part.name << ": not outward";
      area += 0.5 * std::abs(normal[part.axis]);
    }
    EXPECT_NEAR(area, 1.0, 1e-14) << part.name;
  }

  // Conformity: the facets of the tetrahedra, each counted once per cell.
  std::map<std::array<int, 3>, int> facets;
  std::set<std::pair<int, int>> edges;
  for (const auto& t : m.cells)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f{};
      for (int k = 0, at = 0; k < 4; ++k)
        if (k != skip) f[at++] = t[k];
      std::sort(f.begin(), f.end());
      ++facets[f];
      edges.insert({f[0], f[1]}), edges.insert({f[1], f[2]}), edges.insert({f[0], f[2]});
    }
  int on_boundary = 0;
  for (const auto& [f, count] : facets) {
    EXPECT_LE(count, 2);
    on_boundary += count == 1;
  }
  EXPECT_EQ(on_boundary, 12 * n * n);
  Mesh copy = m;
  copy.complete_boundary();
  EXPECT_EQ(copy.boundary.size(), m.boundary.size()) << "a tagged facet is not a facet of the tetrahedra";
  const long V = m.n_vertices(), E = static_cast<long>(edges.size()), F = static_cast<long>(facets.size()),
             T = m.n_cells();
  EXPECT_EQ(V - E + F - T, 1);
  EXPECT_THROW(unit_cube_mesh(0), InputError);
  EXPECT_THROW(unit_cube_mesh(711), InputError);
}

TEST(FESpace, DofCountsOnTetrahedra) {
  const int n = 3;
  const Mesh m = unit_cube_mesh(n);
  const int nv = m.n_vertices(), nc = m.n_cells();
  // edges of the Kuhn cube: 3n(n+1)² along the axes, 3n²(n+1) face diagonals, n³ main
  // diagonals
  const int ne = 3 * n * (n + 1) * (n + 1) + 3 * n * n * (n + 1) + n * n * n;
  EXPECT_EQ(FESpace(m, Element::P0).n_dofs(), nc);
  EXPECT_EQ(FESpace(m, Element::P1).n_dofs(), nv);
  EXPECT_EQ(FESpace(m, Element::P1Bubble).n_dofs(), nv + nc);
  EXPECT_EQ(FESpace(m, Element::P2).n_dofs(), nv + ne);
  const FESpace V(m, Element::P2, 3);
  EXPECT_EQ(V.n_dofs(), 3 * (nv + ne));
  EXPECT_EQ(V.vertex_dof(7, 2), 23);
  EXPECT_THROW(FESpace(m, Element::P1, 4), InputError);
  // P2 dofs on the bottom face: the (2n + 1)² nodes of a P2 grid of the square.
  EXPECT_EQ(FESpace(m, Element::P2).boundary_scalar_dofs({m.part_index("bottom")}).size(),
            static_cast<std::size_t>((2 * n + 1) * (2 * n + 1)));
  // Interpolants reproduce their polynomial spaces exactly.
  expect_exact_interpolants(
      m, [](const Point& p, double) { return 1 + 2 * p.x - p.y + p.x * p.z + 3 * p.y * p.y - p.y * p.z; },
      [](const Point& p, double) { return 0.5 - p.x + 2 * p.y - 3 * p.z; }, {0.2, 0.3, 0.1});
}
