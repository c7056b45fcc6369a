// linalg/masked_cg.cpp — CG on S̃ with a held set, preconditioned by symmetric Gauss–Seidel
// through Eisenstat's trick; see linalg/masked_cg.hpp.
#include "cdyn/linalg/masked_cg.hpp"

#include <algorithm>
#include <cmath>

namespace cdyn {

namespace {

// q_i = (S p)_i on the free rows (0 on the held ones).  S is symmetric, so row i is
// column i of the column-major storage.
void product(const SparseMatrix& S, const std::vector<char>& held, const double* p, double* q) {
  const int n = static_cast<int>(held.size());
  const int* outer = S.outerIndexPtr();
  const int* inner = S.innerIndexPtr();
  const double* v = S.valuePtr();
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    if (!held[i])
      for (int k = outer[i]; k < outer[i + 1]; ++k) sum += v[k] * p[inner[k]];
    q[i] = sum;
  }
}

// max_i |x_i| / s_i: a residual in the units of the stopping test.
double scaled_max(const Eigen::VectorXd& x, const Eigen::VectorXd& s) { return x.cwiseQuotient(s).lpNorm<Eigen::Infinity>(); }

// The sweep after the operator, y += α D^{-1/2} t, r̂ −= α q, with the two reductions the
// next step needs, r̂ᵀr̂ and max |r̂_i| / S_ii^{1/2}: one pass over the vectors instead of
// four.  `omp simd` (compiled with -fopenmp-simd, no OpenMP runtime) lets the compiler
// keep vector partial sums for the reductions, which it must not do on its own (it
// would reassociate floating-point additions).
struct Sweep {
  double rr, proxy;
};
Sweep update(int n, double alpha, const double* t, const double* q, const double* inverse_sqrt_d, double* y,
             double* r_hat) {
  double rr = 0.0, proxy = 0.0;
#pragma omp simd reduction(+ : rr) reduction(max : proxy)
  for (int i = 0; i < n; ++i) {
    y[i] += alpha * t[i] * inverse_sqrt_d[i];
    r_hat[i] -= alpha * q[i];
    rr += r_hat[i] * r_hat[i];
    proxy = std::max(proxy, std::abs(r_hat[i]) * inverse_sqrt_d[i]);
  }
  return {rr, proxy};
}

}  // namespace

MaskedCG::MaskedCG(const SparseMatrix& S)
    : S_(S), sgs_(S), D_(sgs_.sqrt_diagonal().cwiseAbs2()), inverse_sqrt_D_(sgs_.sqrt_diagonal().cwiseInverse()) {}

MaskedCGResult MaskedCG::solve(const std::vector<char>& held, const Eigen::VectorXd& b, Eigen::VectorXd& y,
                               double tol, int max_iterations, bool resume) {
  const int n = sgs_.size();
  const Eigen::VectorXd& sqrt_d = sgs_.sqrt_diagonal();
  MaskedCGResult result;
  // r = D^{1/2} L̂ r̂, from CG's r̂ (into r_; t_ is scratch)
  auto unprecondition = [&]() {
    sgs_.multiply_lower(held, r_hat_.data(), t_.data());
    r_ = t_.cwiseProduct(sqrt_d);
    return scaled_max(r_, D_);
  };

  const bool resuming = resume && resumable_ && y.size() == n;
  resumable_ = false;  // until this solve converges
  if (resuming) {
    // the interrupted iteration's next direction
    result.scaled_residual = last_scaled_;
    if (!(last_scaled_ > tol)) {
      result.converged = true;
      return result;
    }
    p_ = r_hat_ + (rr_next_ / rr_) * p_;
    rr_ = rr_next_;
  } else {
    if (y.size() != n) y = Eigen::VectorXd::Zero(n);
    for (Eigen::VectorXd* v : {&r_, &r_hat_, &p_, &t_, &w_, &q_}) v->resize(n);
    // y = b on A; r = b − S̃y on I, 0 on A (S̃'s rows on I do not see the columns of A).
    for (int i = 0; i < n; ++i) {
      if (held[i]) y[i] = b[i];
      p_[i] = held[i] ? 0.0 : y[i];
    }
    product(S_, held, p_.data(), q_.data());
    r_ = b - q_;
    for (int i = 0; i < n; ++i)
      if (held[i]) r_[i] = 0.0;
    result.scaled_residual = scaled_max(r_, D_);
    if (!(result.scaled_residual > tol)) {
      result.converged = std::isfinite(result.scaled_residual);
      return result;
    }
    // r̂ = L̂⁻¹ D^{-1/2} r
    q_ = r_.cwiseProduct(inverse_sqrt_D_);
    sgs_.solve_lower(held, q_.data(), r_hat_.data());
    rr_ = r_hat_.squaredNorm();
    p_ = r_hat_;
  }
  for (int k = 1; k <= max_iterations; ++k) {
    const double alpha = rr_ / sgs_.apply(held, p_.data(), t_.data(), w_.data(), q_.data());
    const Sweep sweep = update(n, alpha, t_.data(), q_.data(), inverse_sqrt_D_.data(), y.data(), r_hat_.data());
    result.iterations = k;
    if (!std::isfinite(sweep.rr)) {  // (a NaN passes max() unseen, not a sum)
      result.scaled_residual = sweep.rr;
      return result;
    }
    if (sweep.proxy <= tol) {
      result.scaled_residual = unprecondition();
      if (result.scaled_residual <= tol) {
        result.converged = resumable_ = true;
        last_scaled_ = result.scaled_residual;
        rr_next_ = sweep.rr;
        return result;
      }
    }
    const double beta = sweep.rr / rr_;
    rr_ = sweep.rr;
    p_ = r_hat_ + beta * p_;
  }
  result.scaled_residual = unprecondition();
  return result;
}

}  // namespace cdyn
