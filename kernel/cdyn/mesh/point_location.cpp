// point_location.cpp — inverse affine maps, cell by cell.
#include "cdyn/mesh/point_location.hpp"

#include <cmath>
#include <limits>

#include "cdyn/mesh/cell_geometry.hpp"

namespace cdyn {

CellPoint locate(const Mesh& mesh, const Point& p) {
  const double tol = 1e-10;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const CellGeometry K(mesh, c);
    const double dx = p.x - K.a0.x, dy = p.y - K.a0.y;
    std::array<double, 2> xi;
    if (mesh.dim == 1) {
      xi = {dx / K.J[0][0], 0.0};
      if (xi[0] >= -tol && xi[0] <= 1 + tol) return {c, xi};
      continue;
    }
    // ξ = J⁻¹ (p − a0), and J⁻¹ = (J⁻ᵀ)ᵀ.
    xi = {K.invJT[0][0] * dx + K.invJT[1][0] * dy, K.invJT[0][1] * dx + K.invJT[1][1] * dy};
    if (xi[0] >= -tol && xi[1] >= -tol && xi[0] + xi[1] <= 1 + tol) return {c, xi};
  }
  return {};
}

int nearest_vertex(const Mesh& mesh, const Point& p) {
  int best = -1;
  double d = std::numeric_limits<double>::infinity();
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    const double dv = std::hypot(mesh.vertices[v].x - p.x, mesh.vertices[v].y - p.y);
    if (dv < d) d = dv, best = v;
  }
  return best;
}

}  // namespace cdyn
