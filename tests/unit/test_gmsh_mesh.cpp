// test_gmsh_mesh.cpp — the gmsh front end: .geo meshed through the API, .msh 2.2/4.1
// written and read back, physical groups as boundary parts, bad input refused, and
// numbers given to a .geo (read_mesh(path, parameters), as gmsh -setnumber does).
//
// Each check is a number that follows from the geometry (areas, lengths, where the
// boundary lies) or from an identity (Euler's formula, the area of an inscribed
// polygon), not a value copied from a previous run.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "gmsh_fixtures.hpp"

namespace fs = std::filesystem;
using cdyn::Mesh;
using cdyn::testing::expect_input_error;
using cdyn::testing::facet_measure;
using cdyn::testing::part_measure;
using cdyn::testing::scratch_dir;
using cdyn::testing::write_text;

namespace {

std::string data_geo(const std::string& name) {
  return std::string(CDYN_SOURCE_DIR) + "/data/geo/" + name;
}

double boundary_length(const Mesh& m) {
  double s = 0.0;
  for (const auto& f : m.boundary) s += facet_measure(m, f);
  return s;
}

// Physical groups as cdyn sees them: name -> number of facets (boundary parts) or of
// cells (regions, prefixed "region:").
std::map<std::string, int> group_counts(const Mesh& m) {
  std::map<std::string, int> counts;
  for (const auto& name : m.part_names) counts[name] = 0;
  for (const auto& f : m.boundary)
    if (f.part >= 0) ++counts[m.part_names[f.part]];
  for (const auto& name : m.region_names) counts["region:" + name] = 0;
  for (int r : m.cell_region) ++counts["region:" + m.region_names[r]];
  return counts;
}

// The cells as sets of vertex positions (rounded to 1e-12), sorted: two meshes of the
// same triangles compare equal whatever their vertex and cell numbering.
using Position = std::array<long long, 2>;
std::vector<std::vector<Position>> cells_by_position(const Mesh& m) {
  std::vector<std::vector<Position>> cells;
  for (const auto& t : m.cells) {
    std::vector<Position> c;
    for (int i = 0; i <= m.dim; ++i)
      c.push_back({std::llround(m.vertices[t[i]].x * 1e12), std::llround(m.vertices[t[i]].y * 1e12)});
    std::sort(c.begin(), c.end());
    cells.push_back(c);
  }
  std::sort(cells.begin(), cells.end());
  return cells;
}

}  // namespace

// The L-shape [0,1]^2 \ [0.5,1]^2: area 3/4, perimeter 4 (outer 3, re-entrant 1).
TEST(GmshMesh, LShapeFromGeo) {
  const Mesh m = cdyn::read_mesh(data_geo("lshape.geo"));
  ASSERT_EQ(m.dim, 2);
  EXPECT_NEAR(m.measure(), 0.75, 1e-12);
  for (int c = 0; c < m.n_cells(); ++c) EXPECT_GT(m.cell_measure(c), 0.0) << "cell " << c << " not CCW";

  ASSERT_EQ(m.part_names, (std::vector<std::string>{"outer", "reentrant"}));
  ASSERT_EQ(m.region_names, (std::vector<std::string>{"membrane"}));
  ASSERT_EQ(static_cast<int>(m.cell_region.size()), m.n_cells());
  EXPECT_NEAR(boundary_length(m), 4.0, 1e-12);
  EXPECT_NEAR(part_measure(m, m.part_index("outer")), 3.0, 1e-12);
  EXPECT_NEAR(part_measure(m, m.part_index("reentrant")), 1.0, 1e-12);
  EXPECT_EQ(part_measure(m, -1), 0.0) << "the two groups cover the whole boundary";

  // The re-entrant sides lie on x = 0.5 or y = 0.5 with x, y >= 0.5; the outer ones on
  // x = 0, y = 0, x = 1 or y = 1.
  for (const auto& f : m.boundary)
    for (int i = 0; i < 2; ++i) {
      const auto& p = m.vertices[f.vertices[i]];
      if (f.part == m.part_index("reentrant")) {
        EXPECT_TRUE(p.x >= 0.5 - 1e-14 && p.y >= 0.5 - 1e-14);
        EXPECT_TRUE(std::abs(p.x - 0.5) < 1e-14 || std::abs(p.y - 0.5) < 1e-14);
      } else {
        EXPECT_TRUE(p.x < 1e-14 || p.y < 1e-14 || p.x > 1 - 1e-14 || p.y > 1 - 1e-14);
      }
    }

  // Euler's formula for a triangulated disk: V - E + F = 1, each interior edge shared
  // by two triangles (E = (3F + E_boundary)/2), and a closed boundary polygon has as
  // many vertices as edges.
  const int nb = static_cast<int>(m.boundary.size());
  ASSERT_EQ((3 * m.n_cells() + nb) % 2, 0);
  EXPECT_EQ(m.n_vertices() - (3 * m.n_cells() + nb) / 2 + m.n_cells(), 1);
  EXPECT_EQ(static_cast<int>(m.part_vertices({0, 1}).size()), nb);
  EXPECT_LE(m.h_max(), 0.2);  // target size 0.1; gmsh stays within a factor 2 of it
  std::cout << "  lshape: " << m.n_vertices() << " vertices, " << m.n_cells() << " triangles, "
            << nb << " boundary edges, area - 0.75 = " << m.measure() - 0.75
            << ", perimeter - 4 = " << boundary_length(m) - 4.0 << ", h_max = " << m.h_max() << "\n";
}

// The same mesh written as .msh 2.2 and 4.1 and read back is the same mesh.
TEST(GmshMesh, LShapeRoundTripThroughMsh22And41) {
  const fs::path dir = scratch_dir();
  const Mesh direct = cdyn::read_mesh(data_geo("lshape.geo"));
  for (double version : {2.2, 4.1}) {
    const std::string file = (dir / (version == 2.2 ? "lshape22.msh" : "lshape41.msh")).string();
    cdyn::write_msh(data_geo("lshape.geo"), file, version);
    std::ifstream in(file);
    std::string format, number;
    in >> format >> number;
    EXPECT_EQ(format, "$MeshFormat");
    EXPECT_EQ(number, version == 2.2 ? "2.2" : "4.1");

    const Mesh back = cdyn::read_mesh(file);
    SCOPED_TRACE(file);
    EXPECT_EQ(back.dim, direct.dim);
    EXPECT_EQ(back.n_vertices(), direct.n_vertices());
    EXPECT_EQ(back.n_cells(), direct.n_cells());
    EXPECT_EQ(back.boundary.size(), direct.boundary.size());
    EXPECT_EQ(group_counts(back), group_counts(direct));
    EXPECT_NEAR(back.measure(), 0.75, 1e-12);
    EXPECT_NEAR(boundary_length(back), 4.0, 1e-12);
    // Same node order, same coordinates (written with 16 significant digits).
    ASSERT_EQ(back.vertices.size(), direct.vertices.size());
    double dx = 0.0;
    for (int v = 0; v < back.n_vertices(); ++v)
      dx = std::max({dx, std::abs(back.vertices[v].x - direct.vertices[v].x),
                     std::abs(back.vertices[v].y - direct.vertices[v].y)});
    EXPECT_LE(dx, 1e-15);
    EXPECT_EQ(back.cells, direct.cells);
    EXPECT_EQ(cells_by_position(back), cells_by_position(direct));
  }
}

// The disk of radius 20 centred at (0, 20.5).  Its mesh is a polygon inscribed in the
// circle, so  A_polygon <= A <= pi R^2  with  pi R^2 - A = sum_k R^2 (t_k - sin t_k)/2
// <= pi R^2 t_max^2 / 6  (t_k the central angle of boundary edge k, sum t_k = 2 pi).
TEST(GmshMesh, DiskAreaAndContactHalf) {
  const double R = 20.0, yc = 20.5, pi = std::numbers::pi;
  const Mesh m = cdyn::read_mesh(data_geo("disk.geo"));
  ASSERT_EQ(m.dim, 2);
  ASSERT_EQ(m.part_names, (std::vector<std::string>{"contact", "free"}));
  ASSERT_EQ(m.region_names, (std::vector<std::string>{"disk"}));
  EXPECT_EQ(part_measure(m, -1), 0.0);

  double t_max = 0.0, inscribed = 0.0, r_err = 0.0;
  for (const auto& f : m.boundary) {
    const double t = 2.0 * std::asin(facet_measure(m, f) / (2.0 * R));
    t_max = std::max(t_max, t);
    inscribed += 0.5 * R * R * std::sin(t);
    for (int i = 0; i < 2; ++i) {
      const auto& p = m.vertices[f.vertices[i]];
      r_err = std::max(r_err, std::abs(std::hypot(p.x, p.y - yc) - R));
    }
  }
  EXPECT_LE(r_err, 1e-9 * R) << "boundary nodes lie on the circle";
  const double A = m.measure();
  EXPECT_LE(A, pi * R * R);
  EXPECT_GE(A, pi * R * R * (1.0 - t_max * t_max / 6.0));
  EXPECT_NEAR(A, inscribed, 1e-9 * A) << "the mesh area is that of its boundary polygon";

  // Contact on the lower half, free on the upper half, each half the perimeter.
  const int contact = m.part_index("contact"), free = m.part_index("free");
  double y_min = 1e300;
  for (const auto& f : m.boundary)
    for (int i = 0; i < 2; ++i) {
      const double y = m.vertices[f.vertices[i]].y;
      y_min = std::min(y_min, y);
      if (f.part == contact) {
        EXPECT_LE(y, yc + 1e-9);
      } else if (f.part == free) {
        EXPECT_GE(y, yc - 1e-9);
      }
    }
  EXPECT_NEAR(y_min, yc - R, 1e-12) << "lowest point 0.5 mm above the plane y = 0";
  for (int part : {contact, free}) {
    const double L = part_measure(m, part);  // chord 2R sin(t/2) >= R t (1 - t^2/24)
    EXPECT_LE(L, pi * R);
    EXPECT_GE(L, pi * R * (1.0 - t_max * t_max / 24.0));
  }
  std::cout << "  disk: " << m.n_vertices() << " vertices, " << m.n_cells() << " triangles, "
            << "(pi R^2 - A)/(pi R^2) = " << (pi * R * R - A) / (pi * R * R)
            << " <= t_max^2/6 = " << t_max * t_max / 6.0 << "\n";
}

// A 1D model: the bar [0, 2] with physical points "left" and "right".
// lshape.geo is read first, in the same process: both files declare the ONELAB parameter
// "Parameters/mesh size h" (0.1 there, 0.25 here), which must not carry over.
TEST(GmshMesh, BarIn1D) {
  (void)cdyn::read_mesh(data_geo("lshape.geo"));
  const Mesh m = cdyn::read_mesh(data_geo("bar.geo"));
  ASSERT_EQ(m.dim, 1);
  EXPECT_NEAR(m.measure(), 2.0, 1e-12);
  EXPECT_EQ(m.n_vertices(), m.n_cells() + 1);
  EXPECT_EQ(m.n_cells(), 8);  // h = 0.25 on a length of 2
  for (int c = 0; c < m.n_cells(); ++c) EXPECT_GT(m.cell_measure(c), 0.0) << "left to right";
  ASSERT_EQ(m.part_names, (std::vector<std::string>{"left", "right"}));
  ASSERT_EQ(m.boundary.size(), 2u);
  EXPECT_EQ(m.vertices[m.part_vertices({m.part_index("left")}).at(0)].x, 0.0);
  EXPECT_EQ(m.vertices[m.part_vertices({m.part_index("right")}).at(0)].x, 2.0);
  EXPECT_EQ(m.region_names, (std::vector<std::string>{"bar"}));
}

// A hand-written .msh 2.2, independent of gmsh's mesher: the unit square as two
// clockwise triangles (the reader must flip them), an unnamed physical curve (named
// "group<tag>"), no physical surface (all triangles are taken, no regions), and an
// unused node 5 (left out of the numbering).
TEST(GmshMesh, HandWrittenMsh22) {
  const std::string file = write_text(scratch_dir() / "square.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
1 7 "bottom"
$EndPhysicalNames
$Nodes
5
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 9 9 0
$EndNodes
$Elements
4
1 1 2 7 1 1 2
2 1 2 8 2 2 3
3 2 2 0 1 1 3 2
4 2 2 0 1 1 4 3
$EndElements
)");
  const Mesh m = cdyn::read_mesh(file);
  ASSERT_EQ(m.dim, 2);
  EXPECT_EQ(m.n_vertices(), 4);
  EXPECT_EQ(m.n_cells(), 2);
  EXPECT_NEAR(m.measure(), 1.0, 1e-15);
  for (int c = 0; c < m.n_cells(); ++c) EXPECT_NEAR(m.cell_measure(c), 0.5, 1e-15);
  EXPECT_EQ(m.part_names, (std::vector<std::string>{"bottom", "group8"}));
  EXPECT_TRUE(m.region_names.empty());
  EXPECT_TRUE(m.cell_region.empty());
  EXPECT_EQ(m.boundary.size(), 4u);  // 2 tagged + 2 untagged
  EXPECT_NEAR(part_measure(m, -1), 2.0, 1e-15);
  EXPECT_NEAR(boundary_length(m), 4.0, 1e-15);
}

// gmsh writes only the elements of physical groups when there are some: a .geo with
// physical curves but no physical surface must still keep its triangles (and its
// curves' names) in the .msh; write_msh puts them in a physical surface "domain".
TEST(GmshMesh, WriteKeepsCellsWithoutPhysicalSurface) {
  const fs::path dir = scratch_dir();
  const std::string geo = write_text(dir / "square.geo", R"(
Point(1) = {0, 0, 0, 0.25}; Point(2) = {1, 0, 0, 0.25};
Point(3) = {1, 1, 0, 0.25}; Point(4) = {0, 1, 0, 0.25};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("clamped") = {4};
)");
  const Mesh direct = cdyn::read_mesh(geo);
  for (double version : {2.2, 4.1}) {
    const std::string file = (dir / (version == 2.2 ? "s22.msh" : "s41.msh")).string();
    cdyn::write_msh(geo, file, version);
    const Mesh back = cdyn::read_mesh(file);
    SCOPED_TRACE(file);
    EXPECT_EQ(back.n_cells(), direct.n_cells());
    // gmsh renumbers the nodes when it saves a model whose entities are not all in
    // physical groups: the same triangles, numbered differently.
    EXPECT_EQ(cells_by_position(back), cells_by_position(direct));
    EXPECT_EQ(back.region_names, std::vector<std::string>{"domain"});
    EXPECT_NEAR(back.measure(), 1.0, 1e-12);
    EXPECT_NEAR(part_measure(back, back.part_index("clamped")), 1.0, 1e-12);
    EXPECT_NEAR(boundary_length(back), 4.0, 1e-12);
  }
}

TEST(GmshMeshBadInput, MissingFile) {
  expect_input_error((scratch_dir() / "no_such_mesh.msh").string(), "no such file");
  expect_input_error((scratch_dir() / "no_such_geometry.geo").string(), "no such file");
}

TEST(GmshMeshBadInput, GarbageMsh) {
  const fs::path dir = scratch_dir();
  expect_input_error(write_text(dir / "garbage.msh", "this is not a mesh\n%%% 1 2 3\n"));
  expect_input_error(write_text(dir / "truncated.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n"));
  expect_input_error(write_text(dir / "empty.msh", ""), "no mesh elements");
}

TEST(GmshMeshBadInput, GeoSyntaxError) {
  const fs::path dir = scratch_dir();
  expect_input_error(write_text(dir / "syntax.geo", "Point(1) = {0, 0, 0, 0.1};\nPoint(2) = {1, 0, 0 0.1};\n"),
                     "syntax error");
  expect_input_error(write_text(dir / "empty.geo", "// nothing\n"), "no curve, surface or volume");
}

TEST(GmshMeshBadInput, UnsupportedElementsAndFiles) {
  const fs::path dir = scratch_dir();
  const std::string square = R"(
Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
)";
  expect_input_error(write_text(dir / "p2.geo", square + "Mesh.ElementOrder = 2;\n"), "order 2");
  expect_input_error(write_text(dir / "quads.geo", square + "Recombine Surface{1};\n"), "not supported");
  expect_input_error(write_text(dir / "tilted.geo", square + "Rotate {{1, 0, 0}, {0, 0, 0}, 0.5} { Surface{1}; }\n"),
                     "plane z = 0");
  expect_input_error(write_text(dir / "mesh.stl", "solid x\nendsolid x\n"), "unknown mesh file type");
  expect_input_error(dir.string() + "/", "");  // a directory: no extension
}

// gmsh's parser keeps global state; after a syntax error a good file must still read.
TEST(GmshMeshBadInput, GoodFileReadsAfterBadOnes) {
  const fs::path dir = scratch_dir();
  expect_input_error(write_text(dir / "bad.geo", "Line(1) = {1, 2;\n"));
  expect_input_error(write_text(dir / "bad.msh", "$MeshFormat\ngarbage\n"));
  const Mesh m = cdyn::read_mesh(data_geo("lshape.geo"));
  EXPECT_NEAR(m.measure(), 0.75, 1e-12);
}

TEST(GmshMeshBadInput, WriteErrors) {
  const fs::path dir = scratch_dir();
  EXPECT_THROW(cdyn::write_msh(data_geo("lshape.geo"), (dir / "x.msh").string(), 3.0), cdyn::InputError);
  EXPECT_THROW(cdyn::write_msh(data_geo("lshape.geo"), (dir / "x.vtk").string(), 2.2), cdyn::InputError);
  try {
    cdyn::write_msh(data_geo("lshape.geo"), (dir / "no_dir" / "x.msh").string(), 2.2);
    ADD_FAILURE() << "writing into a missing directory did not throw";
  } catch (const cdyn::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("x.msh"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    std::cout << "  [message] " << what << "\n";
  }
}

// ----- parameters of a .geo (read_mesh(path, parameters)) -----------------------------
// A smaller mesh size gives more vertices (about 4× for h/2 in 2D), the default of the
// .geo's DefineConstant is what no parameter gives, a parameterized read leaves nothing
// behind for the next read (gmsh's global state), a parameter used only in an Included
// file is found, and what cannot work is refused with InputError naming
// "setnumber.<name>": a .msh, a name the .geo never mentions, a name the .geo assigns
// itself (h = 0.5;), a non-identifier, a value that is not finite.

using cdyn::InputError;
using cdyn::read_mesh;

namespace {

// The unit square with mesh size `size_expr` at its corners, physical surface "sq".
std::string square_geo(const std::string& header, const std::string& size_expr) {
  return header + "Point(1) = {0, 0, 0, " + size_expr + "}; Point(2) = {1, 0, 0, " + size_expr +
         "};\nPoint(3) = {1, 1, 0, " + size_expr + "}; Point(4) = {0, 1, 0, " + size_expr +
         "};\nLine(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
         "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\nPhysical Surface(\"sq\") = {1};\n";
}

// The parameter an InputError of `f` names.
template <class F>
std::string refused_parameter(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.parameter();
  }
  return "(accepted)";
}

}  // namespace

TEST(GmshParameters, SmallerMeshSizeGivesMoreVertices) {
  const std::string geo = data_geo("two_layer.geo");  // DefineConstant[h = {1.0, ...}]
  const int n_default = read_mesh(geo).n_vertices();
  const int n1 = read_mesh(geo, {{"h", 1.0}}).n_vertices();
  const int n2 = read_mesh(geo, {{"h", 2.0}}).n_vertices();
  const int n05 = read_mesh(geo, {{"h", 0.5}}).n_vertices();
  EXPECT_EQ(n1, n_default);  // the .geo's default is h = 1
  EXPECT_LT(n2, n1);
  EXPECT_LT(n1, n05);
  // In 2D the vertex count goes as 1/h²: about 4× per halving (measured 82, 275, 1001,
  // 3832 vertices for h = 2, 1, 0.5, 0.25: ratios 3.4, 3.6, 3.8, as the boundary
  // vertices grow as 1/h only).
  EXPECT_GT(static_cast<double>(n05) / n1, 3.0);
  EXPECT_LT(static_cast<double>(n05) / n1, 4.5);
  EXPECT_GT(static_cast<double>(n1) / n2, 3.0);
  // Regions and parts are those of the .geo whatever h.
  const cdyn::Mesh fine = read_mesh(geo, {{"h", 0.5}});
  EXPECT_EQ(fine.region_names, (std::vector<std::string>{"soft", "stiff"}));
  EXPECT_NEAR(fine.measure(), 200.0, 1e-10);
  // And the parameter of the disk, lc (a DefineConstant with a long ONELAB name).
  EXPECT_LT(read_mesh(data_geo("disk.geo")).n_vertices(), read_mesh(data_geo("disk.geo"), {{"lc", 1.25}}).n_vertices());
}

TEST(GmshParameters, NothingIsLeftForTheNextRead) {
  const std::string geo = data_geo("two_layer.geo");
  const int n_default = read_mesh(geo).n_vertices();
  read_mesh(geo, {{"h", 0.5}});
  EXPECT_EQ(read_mesh(geo).n_vertices(), n_default);
}

TEST(GmshParameters, ParameterOfAnIncludedFile) {
  const fs::path dir = scratch_dir();
  fs::create_directories(dir / "parts");
  write_text(dir / "parts" / "size.geo", "DefineConstant[ s = {0.5, Name \"Parameters/s\"} ];\n");
  const std::string geo = write_text(dir / "main.geo", square_geo("Include \"parts/size.geo\";\n", "s"));
  EXPECT_LT(read_mesh(geo).n_vertices(), read_mesh(geo, {{"s", 0.1}}).n_vertices());
}

TEST(GmshParameters, RefusedParameters) {
  const fs::path dir = scratch_dir();
  const std::string geo = data_geo("two_layer.geo");
  // a .msh is already meshed
  const std::string msh = (dir / "two_layer.msh").string();
  cdyn::write_msh(geo, msh, 4.1);
  EXPECT_EQ(refused_parameter([&] { read_mesh(msh, {{"h", 0.5}}); }), "setnumber.h");
  // a name the .geo never mentions (a typo would otherwise change nothing)
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"lc", 0.5}}); }), "setnumber.lc");
  // not a variable name, given twice, not finite
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"1h", 0.5}}); }), "setnumber.1h");
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"h", 0.5}, {"h", 0.25}}); }), "setnumber.h");
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"h", std::numeric_limits<double>::infinity()}}); }),
            "setnumber.h");
  // a plain assignment in the .geo overrides the value: refused, with the value it took
  const std::string assigned = write_text(dir / "assigned.geo", square_geo("h = 0.5;\n", "h"));
  try {
    read_mesh(assigned, {{"h", 0.1}});
    FAIL() << "a parameter the .geo assigns itself was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.parameter(), "setnumber.h");
    EXPECT_NE(e.message().find("DefineConstant"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("0.5"), std::string::npos) << e.message();
  }
  // the file still reads without parameters, and a good read follows the refusals
  EXPECT_GT(read_mesh(assigned).n_vertices(), 4);
  EXPECT_EQ(read_mesh(geo, {{"h", 2.0}}).region_names.size(), 2u);
}
