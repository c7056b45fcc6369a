// test_gmsh_mesh_3d.cpp — the gmsh front end on tetrahedra: a .geo meshed in 3D,
// physical volumes as regions and physical surfaces as boundary parts, .msh 2.2 and
// 4.1 written and read back, a hand-written .msh whose tetrahedra must be reoriented,
// and the elements cdyn does not read refused.
//
// Every check is a number that follows from the geometry (the volume of the box and
// the areas of its faces: planar, so exact to round-off) or an identity (Euler's
// formula for a ball, V − E + F − T = 1), not a value copied from a previous run.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "gmsh_fixtures.hpp"

namespace fs = std::filesystem;
using cdyn::Mesh;
using cdyn::testing::expect_input_error;
using cdyn::testing::part_measure;
using cdyn::testing::scratch_dir;
using cdyn::testing::write_text;

namespace {

std::string box_geo() { return std::string(CDYN_SOURCE_DIR) + "/data/geo/box.geo"; }

// V − E + F − T over the tetrahedra's vertices, edges, triangles and cells.
long euler_characteristic(const Mesh& m) {
  std::set<std::array<int, 3>> facets;
  std::set<std::pair<int, int>> edges;
  for (const auto& t : m.cells) {
    std::array<int, 4> s{t[0], t[1], t[2], t[3]};
    std::sort(s.begin(), s.end());
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        edges.insert({s[i], s[j]});
        for (int k = j + 1; k < 4; ++k) facets.insert({s[i], s[j], s[k]});
      }
  }
  return m.n_vertices() - static_cast<long>(edges.size()) + static_cast<long>(facets.size()) - m.n_cells();
}

}  // namespace

// The box [0, 2] × [0, 1] × [0, 1] of data/geo/box.geo: volume 2, faces bottom and top
// (2 each), left (1) and the three others as "sides" (5), one region "solid".
TEST(GmshMesh3D, BoxFromGeo) {
  const Mesh m = cdyn::read_mesh(box_geo());
  ASSERT_EQ(m.dim, 3);
  for (int c = 0; c < m.n_cells(); ++c) ASSERT_GT(m.cell_measure(c), 0.0) << "cell " << c << " is not positive";
  EXPECT_NEAR(m.measure(), 2.0, 1e-13);
  ASSERT_EQ(m.part_names, (std::vector<std::string>{"bottom", "top", "left", "sides"}));
  ASSERT_EQ(m.region_names, (std::vector<std::string>{"solid"}));
  ASSERT_EQ(static_cast<int>(m.cell_region.size()), m.n_cells());
  EXPECT_NEAR(part_measure(m, m.part_index("bottom")), 2.0, 1e-13);
  EXPECT_NEAR(part_measure(m, m.part_index("top")), 2.0, 1e-13);
  EXPECT_NEAR(part_measure(m, m.part_index("left")), 1.0, 1e-13);
  EXPECT_NEAR(part_measure(m, m.part_index("sides")), 5.0, 1e-13);
  EXPECT_EQ(part_measure(m, -1), 0.0) << "the four groups cover the whole boundary";
  for (int v : m.part_vertices({m.part_index("bottom")})) EXPECT_EQ(m.vertices[v].z, 0.0);
  for (int v : m.part_vertices({m.part_index("top")})) EXPECT_NEAR(m.vertices[v].z, 1.0, 1e-15);
  for (int v : m.part_vertices({m.part_index("left")})) EXPECT_EQ(m.vertices[v].x, 0.0);
  EXPECT_EQ(euler_characteristic(m), 1);
  EXPECT_LE(m.h_max(), 0.75);  // target size 0.25: the longest edge measures 0.51 (gmsh 4.8)
  std::cout << "  box: " << m.n_vertices() << " vertices, " << m.n_cells() << " tetrahedra, " << m.boundary.size()
            << " boundary triangles, volume - 2 = " << m.measure() - 2.0 << ", h_max = " << m.h_max() << "\n";
}

// Written as .msh 2.2 and 4.1 and read back: the same mesh, vertex for vertex.
TEST(GmshMesh3D, BoxRoundTripThroughMsh22And41) {
  const fs::path dir = scratch_dir();
  const Mesh direct = cdyn::read_mesh(box_geo(), {{"h", 0.5}});
  for (double version : {2.2, 4.1}) {
    const std::string file = (dir / (version == 2.2 ? "box22.msh" : "box41.msh")).string();
    cdyn::write_msh(box_geo(), file, version, {{"h", 0.5}});
    const Mesh back = cdyn::read_mesh(file);
    SCOPED_TRACE(file);
    EXPECT_EQ(back.dim, 3);
    EXPECT_EQ(back.n_vertices(), direct.n_vertices());
    EXPECT_EQ(back.cells, direct.cells);
    EXPECT_EQ(back.part_names, direct.part_names);
    EXPECT_EQ(back.region_names, direct.region_names);
    ASSERT_EQ(back.boundary.size(), direct.boundary.size());
    for (std::size_t f = 0; f < back.boundary.size(); ++f) {
      EXPECT_EQ(back.boundary[f].vertices, direct.boundary[f].vertices);
      EXPECT_EQ(back.boundary[f].part, direct.boundary[f].part);
    }
    double dx = 0.0;
    for (int v = 0; v < back.n_vertices(); ++v)
      dx = std::max({dx, std::abs(back.vertices[v].x - direct.vertices[v].x),
                     std::abs(back.vertices[v].y - direct.vertices[v].y),
                     std::abs(back.vertices[v].z - direct.vertices[v].z)});
    EXPECT_LE(dx, 1e-15);
    EXPECT_NEAR(back.measure(), 2.0, 1e-13);
  }
}

// A hand-written .msh 2.2: the unit cube's corner tetrahedron (0, e_x, e_y, e_z) given
// negatively oriented (the reader must reorient it) and its neighbour across the face
// x + y + z = 1, the face z = 0 tagged "floor", no physical volume (all tetrahedra are
// taken, no regions); the six other boundary triangles are untagged.
TEST(GmshMesh3D, HandWrittenMsh22IsReoriented) {
  const std::string file = write_text(scratch_dir() / "two_tets.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
2 7 "floor"
$EndPhysicalNames
$Nodes
5
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
5 1 1 1
$EndNodes
$Elements
3
1 2 2 7 1 1 2 3
2 4 2 0 1 1 3 2 4
3 4 2 0 1 2 3 4 5
$EndElements
)");
  const Mesh m = cdyn::read_mesh(file);
  ASSERT_EQ(m.dim, 3);
  ASSERT_EQ(m.n_cells(), 2);
  EXPECT_NEAR(m.cell_measure(0), 1.0 / 6.0, 1e-16);
  // (e_x, e_y, e_z) to (1, 1, 1): det[e_y − e_x, e_z − e_x, (1,1,1) − e_x] / 6 = 1/3
  EXPECT_NEAR(m.cell_measure(1), 1.0 / 3.0, 1e-16);
  EXPECT_EQ(m.part_names, (std::vector<std::string>{"floor"}));
  EXPECT_TRUE(m.region_names.empty());
  EXPECT_EQ(m.boundary.size(), 6u);  // 8 faces, the shared one is interior: 1 tagged + 5 untagged
  EXPECT_NEAR(part_measure(m, m.part_index("floor")), 0.5, 1e-16);
}

TEST(GmshMesh3DBadInput, UnsupportedElements) {
  const fs::path dir = scratch_dir();
  const std::string cube = R"(
Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
)";
  expect_input_error(write_text(dir / "p2.geo", cube + "Extrude {0, 0, 1} { Surface{1}; }\nMesh.ElementOrder = 2;\n"),
                     "order 2");
  expect_input_error(
      write_text(dir / "prisms.geo", cube + "Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; }\n"), "not supported");
  expect_input_error(write_text(dir / "empty.geo", "// nothing\n"), "no curve, surface or volume");
}
