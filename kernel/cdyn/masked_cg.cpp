// masked_cg.cpp — Jacobi-preconditioned CG on S with a held set; see masked_cg.hpp.
#include "cdyn/masked_cg.hpp"

#include <algorithm>
#include <cmath>

namespace cdyn {

namespace {

// q_i = (S p)_i on the free rows (0 on the held ones); returns pᵀq.  S is symmetric, so
// row i is column i of the column-major storage.
double product(const SparseMatrix& S, const std::vector<char>& held, const double* p, double* q) {
  const int n = static_cast<int>(held.size());
  const int* outer = S.outerIndexPtr();
  const int* inner = S.innerIndexPtr();
  const double* v = S.valuePtr();
  double pq = 0.0;
  for (int i = 0; i < n; ++i) {
    if (held[i]) {
      q[i] = 0.0;
      continue;
    }
    double sum = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) sum += v[k] * p[inner[k]];
    q[i] = sum;
    pq += p[i] * sum;
  }
  return pq;
}

}  // namespace

MaskedCGResult masked_cg(const SparseMatrix& S, const Eigen::VectorXd& diagonal, const std::vector<char>& held,
                         const Eigen::VectorXd& b, Eigen::VectorXd& y, double tol, int max_iterations) {
  const int n = static_cast<int>(held.size());
  MaskedCGResult result;
  if (y.size() != n) y = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd Dinv(n), r(n), z(n), p(n), q(n);
  // y = b on A; r = b − S̃y on I, 0 on A; z = D⁻¹r on I, 0 on A (so that p stays 0 on A).
  for (int i = 0; i < n; ++i) {
    Dinv[i] = held[i] ? 0.0 : 1.0 / diagonal[i];
    if (held[i]) y[i] = b[i];
    p[i] = held[i] ? 0.0 : y[i];  // S̃'s rows on I do not see the columns of A
  }
  product(S, held, p.data(), q.data());
  r = b - q;
  for (int i = 0; i < n; ++i)
    if (held[i]) r[i] = 0.0;
  z = Dinv.cwiseProduct(r);
  double rz = r.dot(z);
  double scaled = z.lpNorm<Eigen::Infinity>();
  result.scaled_residual = scaled;
  if (!(scaled > tol)) {
    result.converged = std::isfinite(scaled);
    return result;
  }
  p = z;
  for (int k = 1; k <= max_iterations; ++k) {
    const double alpha = rz / product(S, held, p.data(), q.data());
    y.noalias() += alpha * p;  // Eigen's vectorized sweeps (its reductions keep several
    r.noalias() -= alpha * q;  // partial sums: a hand loop would chain each addition)
    z = Dinv.cwiseProduct(r);
    const double rz_next = r.dot(z);
    scaled = z.lpNorm<Eigen::Infinity>();
    result.iterations = k;
    result.scaled_residual = scaled;
    if (scaled <= tol) {
      result.converged = true;
      return result;
    }
    if (!std::isfinite(scaled)) return result;
    const double beta = rz_next / rz;
    rz = rz_next;
    p = z + beta * p;
  }
  return result;
}

}  // namespace cdyn
