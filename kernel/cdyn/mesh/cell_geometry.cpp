// mesh/cell_geometry.cpp — affine reference-to-physical maps of intervals, triangles and
// tetrahedra.
#include "cdyn/mesh/cell_geometry.hpp"

namespace cdyn {

CellGeometry::CellGeometry(const Mesh& mesh, int cell) : dim(mesh.dim) {
  const auto& t = mesh.cells[cell];
  a0 = mesh.vertices[t[0]];
  for (int k = 1; k <= dim; ++k) {  // column k − 1 of J: a_k − a0
    const Point& a = mesh.vertices[t[k]];
    J[0][k - 1] = a.x - a0.x, J[1][k - 1] = a.y - a0.y, J[2][k - 1] = a.z - a0.z;
  }
  if (dim == 1) {
    det = J[0][0];
    invJT[0][0] = 1.0 / det;
  } else if (dim == 2) {
    det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    // J⁻ᵀ = (1/det) [[J11, −J10], [−J01, J00]]
    invJT[0][0] = J[1][1] / det, invJT[0][1] = -J[1][0] / det;
    invJT[1][0] = -J[0][1] / det, invJT[1][1] = J[0][0] / det;
  } else {
    // J⁻ᵀ = cof(J) / det: entry (i, j) is the cofactor of J_ij.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        invJT[i][j] = J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1];
      }
    det = J[0][0] * invJT[0][0] + J[0][1] * invJT[0][1] + J[0][2] * invJT[0][2];
    for (auto& row : invJT)
      for (double& v : row) v /= det;
  }
}

Point CellGeometry::map(const RefPoint& xi) const {
  Point x = a0;
  for (int k = 0; k < dim; ++k) {
    x.x += J[0][k] * xi[k];
    x.y += J[1][k] * xi[k];
    x.z += J[2][k] * xi[k];
  }
  return x;
}

RefPoint CellGeometry::reference(const Point& x) const {
  // J⁻¹ = (J⁻ᵀ)ᵀ
  const double d[3] = {x.x - a0.x, x.y - a0.y, x.z - a0.z};
  RefPoint xi{0.0, 0.0, 0.0};
  for (int k = 0; k < dim; ++k)
    for (int i = 0; i < dim; ++i) xi[k] += invJT[i][k] * d[i];
  return xi;
}

std::array<double, 3> CellGeometry::gradient(const std::array<double, 3>& g) const {
  std::array<double, 3> out{0.0, 0.0, 0.0};
  for (int i = 0; i < dim; ++i)
    for (int k = 0; k < dim; ++k) out[i] += invJT[i][k] * g[k];
  return out;
}

}  // namespace cdyn
