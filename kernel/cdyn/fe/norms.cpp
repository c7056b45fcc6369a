// fe/norms.cpp — L2 and H1-seminorm errors by high-order cell quadrature.
#include "cdyn/fe/norms.hpp"

#include <cmath>

#include "cdyn/mesh/cell_geometry.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fe/quadrature.hpp"

namespace cdyn {

double l2_error(const FESpace& W, const Eigen::VectorXd& U, const Field& u, double t) {
  if (W.components() != 1) throw InputError("l2_error: a scalar space is expected");
  const QuadratureRule q = cell_quadrature(W.dim(), 2 * W.degree() + 4);
  double e2 = 0.0;
  for (int c = 0; c < W.mesh().n_cells(); ++c) {
    const CellGeometry K(W.mesh(), c);
    for (int p = 0; p < q.size(); ++p) {
      const Point x = K.map(q.points[p]);
      const double d = u(x, t) - W.value_in_cell(U, c, q.points[p]);
      e2 += q.weights[p] * K.det * d * d;
    }
  }
  return std::sqrt(e2);
}

double h1_seminorm_error(const FESpace& W, const Eigen::VectorXd& U, const GradientField& grad_u, double t) {
  if (W.components() != 1) throw InputError("h1_seminorm_error: a scalar space is expected");
  // (the exact gradient is given in the plane: a 3D mesh would lose ∂u/∂z unseen)
  if (W.dim() > 2) throw InputError("h1_seminorm_error: a 1D or 2D mesh is expected (the gradient has two components)");
  const QuadratureRule q = cell_quadrature(W.dim(), 2 * W.degree() + 4);
  const int n = W.local_dofs();
  std::vector<std::array<double, 3>> g(n);
  double e2 = 0.0;
  for (int c = 0; c < W.mesh().n_cells(); ++c) {
    const CellGeometry K(W.mesh(), c);
    const auto d = W.cell_dofs(c);
    for (int p = 0; p < q.size(); ++p) {
      shape_gradients(W.element(), W.dim(), q.points[p], g.data());
      std::array<double, 2> gh{0.0, 0.0};
      for (int i = 0; i < n; ++i) {
        const auto gi = K.gradient(g[i]);
        gh[0] += U[d[i]] * gi[0], gh[1] += U[d[i]] * gi[1];
      }
      const Point x = K.map(q.points[p]);
      const auto ge = grad_u(x.x, x.y, t);
      e2 += q.weights[p] * K.det * ((ge[0] - gh[0]) * (ge[0] - gh[0]) + (ge[1] - gh[1]) * (ge[1] - gh[1]));
    }
  }
  return std::sqrt(e2);
}

}  // namespace cdyn
