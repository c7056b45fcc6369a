// mesh/point_location.cpp — inverse affine maps, cell by cell.
#include "cdyn/mesh/point_location.hpp"

#include <cmath>
#include <limits>

#include "cdyn/mesh/cell_geometry.hpp"

namespace cdyn {

CellPoint locate(const Mesh& mesh, const Point& p) {
  const double tol = 1e-10;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const CellGeometry K(mesh, c);
    const RefPoint xi = K.reference(p);
    // inside: every barycentric coordinate ξ_k and 1 − Σ ξ_k is ≥ −tol
    double sum = 0.0;
    bool inside = true;
    for (int k = 0; k < mesh.dim; ++k) {
      inside = inside && xi[k] >= -tol;
      sum += xi[k];
    }
    if (inside && sum <= 1 + tol) return {c, xi};
  }
  return {};
}

int nearest_vertex(const Mesh& mesh, const Point& p) {
  int best = -1;
  double d = std::numeric_limits<double>::infinity();
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    const double dv = std::hypot(mesh.vertices[v].x - p.x, mesh.vertices[v].y - p.y, mesh.vertices[v].z - p.z);
    if (dv < d) d = dv, best = v;
  }
  return best;
}

}  // namespace cdyn
