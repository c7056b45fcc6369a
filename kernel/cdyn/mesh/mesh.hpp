// mesh/mesh.hpp — simplicial meshes: intervals (1D), triangles (2D), tetrahedra (3D).
//
// The seed's triangulation 𝒯^h ("A model problem": a regular mesh of Ω, its vertex
// set 𝒜 where the constraints act).  A mesh is geometry and topology only: vertex
// coordinates, cells given by their vertices, and the boundary facets (points in 1D,
// edges in 2D, triangles in 3D), each facet tagged with the boundary part it belongs
// to.  It knows nothing of finite elements.
//
// Conventions
//  - Coordinates are stored as (x, y, z); a 1D mesh has y = z = 0, a 2D mesh z = 0.
//  - A cell has dim + 1 vertices, stored in cells[c][0..dim] (the entries after dim are
//    unused); they are ordered so that the Jacobian of the map from the reference cell
//    is positive: left to right in 1D, counter-clockwise in 2D, a positively oriented
//    tetrahedron in 3D.
//  - A facet has dim vertices, vertices[0..dim-1] (the others unused).
//  - Boundary parts have names ("left", "bottom", or a gmsh physical group name).
//    A facet on the topological boundary that belongs to no named part has part -1.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace cdyn {

struct Point {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

// Coordinates (ξ, η, ζ) of a point of the reference cell (those beyond the cell's
// dimension are 0): the interval [0, 1], the triangle (0,0), (1,0), (0,1), the
// tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1).
using RefPoint = std::array<double, 3>;

struct BoundaryFacet {
  std::array<int, 3> vertices{-1, -1, -1};  // the first dim entries are used
  int part = -1;                            // index into Mesh::part_names, or -1
};

using Cell = std::array<int, 4>;  // the first dim + 1 entries are used

// A facet as the sorted set of its dim vertices, the unused entries −1: the key under
// which a cell's facet and a boundary facet are the same.
using FacetKey = std::array<int, 3>;
FacetKey facet_key(const std::array<int, 3>& vertices, int dim);
// The facet of a cell opposite its vertex `skip` (0 … dim), as a key.
FacetKey cell_facet(const Cell& cell, int dim, int skip);

struct Mesh {
  int dim = 2;                                 // 1 (intervals), 2 (triangles) or 3 (tetrahedra)
  std::vector<Point> vertices;                 // coordinates
  std::vector<Cell> cells;                     // vertices of each cell
  std::vector<BoundaryFacet> boundary;         // every boundary facet, tagged
  std::vector<std::string> part_names;         // boundary part names
  std::vector<int> cell_region;                // region tag of each cell (gmsh physical group), or empty
  std::vector<std::string> region_names;       // names of those regions
  // A sub-mesh's vertices on a boundary part through facets of another subdomain's
  // cells (mesh/sub_mesh.hpp), as (part, vertex) pairs: part_vertices counts them.
  std::vector<std::array<int, 2>> parts_elsewhere;

  int n_vertices() const { return static_cast<int>(vertices.size()); }
  int n_cells() const { return static_cast<int>(cells.size()); }
  int vertices_per_cell() const { return dim + 1; }

  // Index of a boundary part by name; throws InputError naming the part if absent.
  int part_index(const std::string& name) const;

  // The vertices lying on the named boundary parts (sorted, unique).
  std::vector<int> part_vertices(const std::vector<int>& parts) const;

  // Signed measure of a cell: its length (1D), area (2D) or volume (3D), positive for
  // cells ordered as the conventions above say.
  double cell_measure(int c) const;

  // Sum of the cell measures: |Omega|.
  double measure() const;

  // Largest cell diameter h.
  double h_max() const;

  // Tags every facet on the topological boundary (a facet seen by exactly one cell)
  // that is not yet in `boundary`, with part -1.  Readers call it after adding the
  // named facets they know.
  void complete_boundary();

  // Throws InputError (prefixed by `source`) if cells reference missing vertices,
  // have non-positive measure, or the mesh is empty.
  void check(const std::string& source) const;
};

// Built-in structured meshes (the `mesh.kind` values of docs/scenes.md).

// [0, length] split into n equal intervals; boundary parts "left" (x = 0) and
// "right" (x = length).
Mesh interval_mesh(int n, double length = 1.0);

// The unit square (or [0,lx]x[0,ly]) with n x n cells, each split along its
// lower-left to upper-right diagonal into two triangles, as FreeFEM's square(n,n).
// Vertex numbering is row by row from (0,0), as FreeFEM's.  Boundary parts
// "bottom", "right", "top", "left" (FreeFEM labels 1, 2, 3, 4).
Mesh unit_square_mesh(int n, double lx = 1.0, double ly = 1.0);

// The unit cube with n x n x n cells, each split into six tetrahedra around its main
// diagonal (the Kuhn, or Freudenthal, split: the tetrahedra {x_a >= x_b >= x_c} of the
// cell's local coordinates, one per ordering (a, b, c) of the axes).  Every face of a
// cell is then cut along its diagonal from the lowest to the highest corner, the same
// from both sides, so the mesh is conforming.  Vertex i + (n+1)(j + (n+1)k) sits at
// (i, j, k)/n.  Boundary parts, in the order of FreeFEM's cube(n,n,n) labels 1..6:
// "front" (y = 0), "right" (x = 1), "back" (y = 1), "left" (x = 0), "bottom" (z = 0),
// "top" (z = 1); two triangles per cell face, ordered counter-clockwise seen from
// outside (their normal (b − a) × (c − a) points out of the cube).
Mesh unit_cube_mesh(int n);

}  // namespace cdyn
