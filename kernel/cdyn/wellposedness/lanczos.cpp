// lanczos.cpp — Lanczos with full reorthogonalization, largest Ritz pair.
#include "cdyn/wellposedness/lanczos.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "cdyn/base/error.hpp"

namespace cdyn {

LanczosPair lanczos_largest(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& T,
                            const Eigen::VectorXd& start, int max_steps,
                            const std::function<bool(const LanczosPair&)>& converged) {
  const Eigen::Index n = start.size();
  const double norm0 = start.norm();
  if (n == 0 || !(norm0 > 0.0)) throw InputError("Lanczos: the start vector is zero");
  const int m = static_cast<int>(std::min<Eigen::Index>(max_steps, n));
  Eigen::MatrixXd V(n, m);  // the orthonormal Krylov basis
  Eigen::VectorXd alpha(m), beta(m);
  V.col(0) = start / norm0;
  LanczosPair pair;
  for (int j = 0; j < m; ++j) {
    Eigen::VectorXd w = T(V.col(j));
    alpha[j] = V.col(j).dot(w);
    // Full reorthogonalization, twice ("twice is enough", Parlett): the basis stays
    // orthogonal to working precision, so no spurious copies of converged Ritz values.
    for (int pass = 0; pass < 2; ++pass) w -= V.leftCols(j + 1) * (V.leftCols(j + 1).transpose() * w);
    beta[j] = w.norm();

    // Ritz pairs of the tridiagonal T_j = tridiag(β, α, β).
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig;
    Eigen::MatrixXd Tj = Eigen::MatrixXd::Zero(j + 1, j + 1);
    for (int i = 0; i <= j; ++i) {
      Tj(i, i) = alpha[i];
      if (i > 0) Tj(i, i - 1) = Tj(i - 1, i) = beta[i - 1];
    }
    eig.compute(Tj);
    const Eigen::VectorXd s = eig.eigenvectors().col(j);  // ascending: the last is the largest
    pair.value = eig.eigenvalues()[j];
    pair.second = j > 0 ? eig.eigenvalues()[j - 1] : pair.value;
    pair.steps = j + 1;
    // An invariant Krylov space (β_j at round-off relative to the operator's scale):
    // the Ritz pairs are eigenpairs.
    const bool invariant = beta[j] <= 1e-14 * std::max(std::abs(pair.value), std::abs(alpha[j]));
    pair.residual = invariant ? 0.0 : beta[j] * std::abs(s[j]);
    if (invariant || j + 1 == m || converged(pair)) {
      pair.vector = V.leftCols(j + 1) * s;
      pair.vector.normalize();
      return pair;
    }
    V.col(j + 1) = w / beta[j];
  }
  return pair;  // not reached: m ≥ 1
}

}  // namespace cdyn
