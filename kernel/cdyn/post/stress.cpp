// post/stress.cpp — cell means of ε(u_h) and σ, their vertex averages (see the header).
#include "cdyn/post/stress.hpp"

#include <array>
#include <cmath>
#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/element.hpp"
#include "cdyn/fe/quadrature.hpp"
#include "cdyn/mesh/cell_geometry.hpp"

namespace cdyn {

SymmetricTensor isotropic_stress(const SymmetricTensor& e, double lambda, double mu) {
  const double trace = e.xx + e.yy + e.zz;
  return {lambda * trace + 2.0 * mu * e.xx, lambda * trace + 2.0 * mu * e.yy, lambda * trace + 2.0 * mu * e.zz,
          2.0 * mu * e.xy,                  2.0 * mu * e.xz,                  2.0 * mu * e.yz};
}

double von_mises(const SymmetricTensor& s) {
  const double a = s.xx - s.yy, b = s.yy - s.zz, c = s.zz - s.xx;
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s.xy * s.xy + s.xz * s.xz + s.yz * s.yz));
}

std::vector<StressState> cell_stress(const FESpace& W, const Eigen::VectorXd& U_full, const CellCoefficient& lambda,
                                     const CellCoefficient& mu) {
  const int dim = W.dim();
  if ((dim != 2 && dim != 3) || W.components() != dim)
    throw InputError("cell_stress: one component per coordinate of a 2D or 3D mesh is expected");
  if (U_full.size() != W.n_dofs())
    throw InputError("cell_stress: " + std::to_string(U_full.size()) + " coefficients for a space of " +
                     std::to_string(W.n_dofs()) + " dofs");
  const Mesh& mesh = W.mesh();
  for (const CellCoefficient* a : {&lambda, &mu})
    if (!a->is_uniform() && static_cast<int>(a->per_cell().size()) != mesh.n_cells())
      throw InputError("cell_stress: one Lamé value per cell expected");

  // ∇u_h has degree deg(W) − 1 on a cell: a rule of that degree gives its mean exactly.
  const QuadratureRule q = cell_quadrature(dim, W.degree() - 1);
  const int n = W.local_dofs();
  std::vector<std::vector<std::array<double, 3>>> ref(q.size(), std::vector<std::array<double, 3>>(n));
  double weight_sum = 0.0;  // the reference cell's measure
  for (int p = 0; p < q.size(); ++p) {
    shape_gradients(W.element(), dim, q.points[p], ref[p].data());
    weight_sum += q.weights[p];
  }

  std::vector<StressState> out(mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const CellGeometry K(mesh, c);
    const auto d = W.cell_dofs(c);
    double grad[3][3] = {};  // mean of ∂_j u_i (the third row and column stay 0 in the plane)
    for (int p = 0; p < q.size(); ++p) {
      const double w = q.weights[p] / weight_sum;  // the mean: Σ w_p = 1 (det J cancels)
      for (int i = 0; i < n; ++i) {
        const std::array<double, 3> g = K.gradient(ref[p][i]);
        for (int k = 0; k < dim; ++k) {
          const double u = U_full[W.dof(d[i], k)];
          for (int j = 0; j < dim; ++j) grad[k][j] += w * u * g[j];
        }
      }
    }
    StressState& s = out[c];
    s.epsilon = {grad[0][0],
                 grad[1][1],
                 grad[2][2],
                 0.5 * (grad[0][1] + grad[1][0]),
                 0.5 * (grad[0][2] + grad[2][0]),
                 0.5 * (grad[1][2] + grad[2][1])};
    s.sigma = isotropic_stress(s.epsilon, lambda[c], mu[c]);
    s.von_mises = von_mises(s.sigma);
  }
  return out;
}

std::vector<StressState> vertex_stress(const Mesh& mesh, const std::vector<StressState>& cells) {
  if (static_cast<int>(cells.size()) != mesh.n_cells())
    throw InputError("vertex_stress: one value per cell expected");
  std::vector<StressState> out(mesh.n_vertices());
  std::vector<double> area(mesh.n_vertices(), 0.0);
  auto add = [](SymmetricTensor& to, const SymmetricTensor& t, double w) {
    to.xx += w * t.xx;
    to.yy += w * t.yy;
    to.zz += w * t.zz;
    to.xy += w * t.xy;
    to.xz += w * t.xz;
    to.yz += w * t.yz;
  };
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const double w = mesh.cell_measure(c);
    for (int k = 0; k < mesh.vertices_per_cell(); ++k) {
      const int v = mesh.cells[c][k];
      add(out[v].epsilon, cells[c].epsilon, w);
      add(out[v].sigma, cells[c].sigma, w);
      area[v] += w;
    }
  }
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    if (area[v] > 0.0) {  // (a vertex of no cell keeps zeros)
      const double inv = 1.0 / area[v];
      for (SymmetricTensor* t : {&out[v].epsilon, &out[v].sigma}) {
        t->xx *= inv;
        t->yy *= inv;
        t->zz *= inv;
        t->xy *= inv;
        t->xz *= inv;
        t->yz *= inv;
      }
    }
    out[v].von_mises = von_mises(out[v].sigma);
  }
  return out;
}

}  // namespace cdyn
