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

PlaneStrainTensor plane_strain_stress(const PlaneStrainTensor& e, double lambda, double mu) {
  const double trace = e.xx + e.yy;  // ε_zz = 0
  return {lambda * trace + 2.0 * mu * e.xx, lambda * trace + 2.0 * mu * e.yy, lambda * trace, 2.0 * mu * e.xy};
}

double von_mises(const PlaneStrainTensor& s) {
  const double a = s.xx - s.yy, b = s.yy - s.zz, c = s.zz - s.xx;
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * s.xy * s.xy);
}

std::vector<StressState> cell_stress(const FESpace& W, const Eigen::VectorXd& U_full, const CellCoefficient& lambda,
                                     const CellCoefficient& mu) {
  if (W.components() != 2 || W.dim() != 2) throw InputError("cell_stress: a 2-component space on a 2D mesh is expected");
  if (U_full.size() != W.n_dofs())
    throw InputError("cell_stress: " + std::to_string(U_full.size()) + " coefficients for a space of " +
                     std::to_string(W.n_dofs()) + " dofs");
  const Mesh& mesh = W.mesh();
  for (const CellCoefficient* a : {&lambda, &mu})
    if (!a->is_uniform() && static_cast<int>(a->per_cell().size()) != mesh.n_cells())
      throw InputError("cell_stress: one Lamé value per cell expected");

  // ∇u_h has degree deg(W) − 1 on a cell: a rule of that degree gives its mean exactly.
  const QuadratureRule q = cell_quadrature(2, W.degree() - 1);
  const int n = W.local_dofs();
  std::vector<std::vector<std::array<double, 3>>> ref(q.size(), std::vector<std::array<double, 3>>(n));
  double weight_sum = 0.0;  // the reference cell's measure
  for (int p = 0; p < q.size(); ++p) {
    shape_gradients(W.element(), 2, q.points[p], ref[p].data());
    weight_sum += q.weights[p];
  }

  std::vector<StressState> out(mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const CellGeometry K(mesh, c);
    const auto d = W.cell_dofs(c);
    double grad[2][2] = {{0.0, 0.0}, {0.0, 0.0}};  // mean of ∂_j u_i
    for (int p = 0; p < q.size(); ++p) {
      const double w = q.weights[p] / weight_sum;  // the mean: Σ w_p = 1 (det J cancels)
      for (int i = 0; i < n; ++i) {
        const std::array<double, 3> g = K.gradient(ref[p][i]);
        for (int k = 0; k < 2; ++k) {
          const double u = U_full[W.dof(d[i], k)];
          grad[k][0] += w * u * g[0];
          grad[k][1] += w * u * g[1];
        }
      }
    }
    StressState& s = out[c];
    s.epsilon = {grad[0][0], grad[1][1], 0.0, 0.5 * (grad[0][1] + grad[1][0])};
    s.sigma = plane_strain_stress(s.epsilon, lambda[c], mu[c]);
    s.von_mises = von_mises(s.sigma);
  }
  return out;
}

std::vector<StressState> vertex_stress(const Mesh& mesh, const std::vector<StressState>& cells) {
  if (static_cast<int>(cells.size()) != mesh.n_cells())
    throw InputError("vertex_stress: one value per cell expected");
  std::vector<StressState> out(mesh.n_vertices());
  std::vector<double> area(mesh.n_vertices(), 0.0);
  auto add = [](PlaneStrainTensor& to, const PlaneStrainTensor& t, double w) {
    to.xx += w * t.xx;
    to.yy += w * t.yy;
    to.zz += w * t.zz;
    to.xy += w * t.xy;
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
      for (PlaneStrainTensor* t : {&out[v].epsilon, &out[v].sigma}) {
        t->xx *= inv;
        t->yy *= inv;
        t->zz *= inv;
        t->xy *= inv;
      }
    }
    out[v].von_mises = von_mises(out[v].sigma);
  }
  return out;
}

}  // namespace cdyn
