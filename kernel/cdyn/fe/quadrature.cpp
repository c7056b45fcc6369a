// fe/quadrature.cpp — Gauss–Legendre (Golub–Welsch), collapsed triangle and
// Grundmann–Möller tetrahedron rules.
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

QuadratureRule grundmann_moller(int s) {
  if (s < 0) throw std::invalid_argument("grundmann_moller: s must be >= 0");
  // Grundmann & Möller (1978), on the n-simplex of volume 1/n! (n = 3):
  //   ∫ f ≈ Σ_{i=0..s} w_i Σ_{|β| = s − i} f(λ = (2β + 1)/(d + n − 2i)),
  //   w_i = (−1)^i 2^{−2s} (d + n − 2i)^d / (i! (d + n − i)!),   d = 2s + 1,
  // β ∈ N^{n+1} the multi-indices of sum s − i and λ the barycentric coordinates of the
  // point (they sum to 1); the reference coordinates are (λ1, λ2, λ3).
  constexpr int n = 3;
  const int d = 2 * s + 1;
  QuadratureRule q;
  for (int i = 0; i <= s; ++i) {
    const double den = d + n - 2 * i;
    // (factorials by products: exact in double up to 22!, where tgamma is not)
    double factorials = 1.0;
    for (int k = 2; k <= i; ++k) factorials *= k;
    for (int k = 2; k <= d + n - i; ++k) factorials *= k;
    const double w = (i % 2 ? -1.0 : 1.0) * std::ldexp(1.0, -2 * s) * std::pow(den, d) / factorials;
    const int m = s - i;
    for (int b1 = 0; b1 <= m; ++b1)
      for (int b2 = 0; b1 + b2 <= m; ++b2)
        for (int b3 = 0; b1 + b2 + b3 <= m; ++b3) {  // β0 = m − b1 − b2 − b3
          q.points.push_back({(2 * b1 + 1) / den, (2 * b2 + 1) / den, (2 * b3 + 1) / den});
          q.weights.push_back(w);
        }
  }
  return q;
}

QuadratureRule cell_quadrature(int dim, int degree) {
  degree = std::max(degree, 0);
  if (dim == 1) return gauss_legendre(degree / 2 + 1);
  if (dim == 3) return grundmann_moller(degree / 2);  // degree 2s + 1 >= degree
  if (dim != 2) throw std::invalid_argument("cell_quadrature: dim must be 1, 2 or 3");
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
