// mesh/point_location.hpp — finding the cell that contains a point (for probes: the value of
// u_h at a point is FESpace::value_in_cell at the cell and reference point found here).
// Not part of the seed's method; geometry only.
#pragma once

#include <array>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

struct CellPoint {
  int cell = -1;                 // -1: outside the mesh
  RefPoint xi{};                 // reference coordinates in that cell
};

// The first cell containing p (barycentric coordinates ≥ −1e-10, so points on edges
// and vertices are found); a linear search, meant for a handful of probes.
CellPoint locate(const Mesh& mesh, const Point& p);

// The vertex nearest to p.
int nearest_vertex(const Mesh& mesh, const Point& p);

}  // namespace cdyn
