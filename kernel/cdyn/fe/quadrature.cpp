// fe/quadrature.cpp — Gauss–Legendre (Golub–Welsch) and collapsed triangle rules.
#include "cdyn/fe/quadrature.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cdyn {

QuadratureRule gauss_legendre(int n) {
  if (n < 1) throw std::invalid_argument("gauss_legendre: n must be >= 1");
  // Golub–Welsch: the nodes on [−1, 1] are the eigenvalues of the symmetric
  // tridiagonal Jacobi matrix of the Legendre recurrence, β_k = k / sqrt(4k² − 1);
  // the weights are 2 (first component of the normalised eigenvector)².
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) J(k, k - 1) = J(k - 1, k) = k / std::sqrt(4.0 * k * k - 1.0);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(J);
  QuadratureRule q;
  for (int i = 0; i < n; ++i) {
    const double v0 = eig.eigenvectors()(0, i);
    q.points.push_back({0.5 * (eig.eigenvalues()(i) + 1.0), 0.0, 0.0});  // map to [0, 1]
    q.weights.push_back(v0 * v0);                                    // 2 v0² × ½
  }
  return q;
}

QuadratureRule cell_quadrature(int dim, int degree) {
  degree = std::max(degree, 0);
  if (dim == 1) return gauss_legendre(degree / 2 + 1);
  if (dim != 2) throw std::invalid_argument("cell_quadrature: dim must be 1 or 2");
  // ∫_T p(ξ, η) = ∫₀¹∫₀¹ p(s(1 − t), t) (1 − t) ds dt: degree p in s, p + 1 in t.
  const QuadratureRule qs = gauss_legendre(degree / 2 + 1);
  const QuadratureRule qt = gauss_legendre((degree + 1) / 2 + 1);
  QuadratureRule q;
  for (int j = 0; j < qt.size(); ++j)
    for (int i = 0; i < qs.size(); ++i) {
      const double s = qs.points[i][0], t = qt.points[j][0];
      q.points.push_back({s * (1.0 - t), t, 0.0});
      q.weights.push_back(qs.weights[i] * qt.weights[j] * (1.0 - t));
    }
  return q;
}

}  // namespace cdyn
