// cell_geometry.cpp — affine reference-to-physical maps.
#include "cdyn/mesh/cell_geometry.hpp"

namespace cdyn {

CellGeometry::CellGeometry(const Mesh& mesh, int cell) : dim(mesh.dim) {
  const auto& t = mesh.cells[cell];
  a0 = mesh.vertices[t[0]];
  const Point& a1 = mesh.vertices[t[1]];
  if (dim == 1) {
    J[0][0] = a1.x - a0.x;
    det = J[0][0];
    invJT[0][0] = 1.0 / det;
    return;
  }
  const Point& a2 = mesh.vertices[t[2]];
  J[0][0] = a1.x - a0.x, J[0][1] = a2.x - a0.x;
  J[1][0] = a1.y - a0.y, J[1][1] = a2.y - a0.y;
  det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  // J⁻ᵀ = (1/det) [[J11, −J10], [−J01, J00]]
  invJT[0][0] = J[1][1] / det, invJT[0][1] = -J[1][0] / det;
  invJT[1][0] = -J[0][1] / det, invJT[1][1] = J[0][0] / det;
}

Point CellGeometry::map(const std::array<double, 2>& xi) const {
  if (dim == 1) return {a0.x + J[0][0] * xi[0], 0.0};
  return {a0.x + J[0][0] * xi[0] + J[0][1] * xi[1], a0.y + J[1][0] * xi[0] + J[1][1] * xi[1]};
}

std::array<double, 2> CellGeometry::gradient(const std::array<double, 2>& g) const {
  if (dim == 1) return {invJT[0][0] * g[0], 0.0};
  return {invJT[0][0] * g[0] + invJT[0][1] * g[1], invJT[1][0] * g[0] + invJT[1][1] * g[1]};
}

}  // namespace cdyn
