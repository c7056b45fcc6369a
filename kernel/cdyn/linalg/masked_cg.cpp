// linalg/masked_cg.cpp — CG on S̃ with a held set, preconditioned by symmetric Gauss–Seidel
// through Eisenstat's trick; see linalg/masked_cg.hpp.
#include "cdyn/linalg/masked_cg.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

namespace {

// max_i |x_i| / s_i: a residual in the units of the stopping test.
double scaled_max(const Eigen::VectorXd& x, const Eigen::VectorXd& s) { return max_abs(x, &s); }

// The same over the listed free rows (x vanishes on the others), NaN if an entry is NaN.
double scaled_max(const std::vector<int>& free, const Eigen::VectorXd& x, const Eigen::VectorXd& s) {
  double m = 0.0;
  bool nan = false;
  for (int i : free) {
    const double a = std::abs(x[i]) / s[i];
    nan = nan || std::isnan(a);
    m = std::max(m, a);
  }
  return nan ? std::numeric_limits<double>::quiet_NaN() : m;
}

// The rows an iteration visits: all of them (the identity), or the free ones alone
// (listed in increasing order) when most are held — the vectors vanish on the held rows,
// where the whole-vector loops only add zeros.
struct AllRows {
  int size;
  int operator[](int k) const { return k; }
};
struct ListedRows {
  const std::vector<int>& rows;
  int size;
  int operator[](int k) const { return rows[k]; }
};

// The sweep after the operator, y += α D^{-1/2} t, r̂ −= α q, with the two reductions the
// next step needs, r̂ᵀr̂ and max |r̂_i| / S_ii^{1/2}: one pass over the vectors instead of
// four.  By blocks of kBlock rows (linalg/parallel.hpp, rule 2): the blocks are shared
// among the threads, and r̂ᵀr̂ is the sum of the blocks' sums in order, the same on any
// number of threads (a maximum is exact in any order).  Within a block `omp simd` lets
// the compiler keep vector partial sums, which it must not do on its own (it would
// reassociate floating-point additions).  `block_rr`: work space, one entry per block.
struct Sweep {
  double rr, proxy;
};
template <class Rows>
Sweep update(Rows I, double alpha, const double* t, const double* q, const double* inverse_sqrt_d, double* y,
             double* r_hat, std::vector<double>& block_rr) {
  const int m = I.size, blocks = block_count(m);
  block_rr.resize(blocks);
  double proxy = 0.0;
#pragma omp parallel for schedule(static) reduction(max : proxy) if (5L * m >= kParallelWork)
  for (int b = 0; b < blocks; ++b) {
    const int end = std::min(m, (b + 1) * kBlock);
    double rr = 0.0, block_proxy = 0.0;
#pragma omp simd reduction(+ : rr) reduction(max : block_proxy)
    for (int k = b * kBlock; k < end; ++k) {
      const int i = I[k];
      y[i] += alpha * t[i] * inverse_sqrt_d[i];
      r_hat[i] -= alpha * q[i];
      rr += r_hat[i] * r_hat[i];
      block_proxy = std::max(block_proxy, std::abs(r_hat[i]) * inverse_sqrt_d[i]);
    }
    block_rr[b] = rr;
    proxy = std::max(proxy, block_proxy);
  }
  double rr = 0.0;
  for (double s : block_rr) rr += s;
  return {rr, proxy};
}

// p = r̂ + β p, shared among the threads by rows.
template <class Rows>
void next_direction(Rows I, const double* r_hat, double beta, double* p) {
#pragma omp parallel for schedule(static) if (2L * I.size >= kParallelWork)
  for (int k = 0; k < I.size; ++k) p[I[k]] = r_hat[I[k]] + beta * p[I[k]];
}

// xᵀy over the free rows, by blocks of kBlock of them (as update's sum).
double dot_on(ListedRows I, const double* x, const double* y, std::vector<double>& block_sum) {
  const int m = I.size, blocks = block_count(m);
  block_sum.resize(blocks);
#pragma omp parallel for schedule(static) if (2L * m >= kParallelWork)
  for (int b = 0; b < blocks; ++b) {
    const int end = std::min(m, (b + 1) * kBlock);
    double s = 0.0;
    for (int k = b * kBlock; k < end; ++k) s += x[I[k]] * y[I[k]];
    block_sum[b] = s;
  }
  double s = 0.0;
  for (double v : block_sum) s += v;
  return s;
}

}  // namespace

MaskedCG::MaskedCG(const SparseMatrix& S)
    : sgs_(S), D_(sgs_.sqrt_diagonal().cwiseAbs2()), inverse_sqrt_D_(sgs_.sqrt_diagonal().cwiseInverse()) {}

// y = b on A; r = b − S̃y on I, 0 on A (S̃'s rows on I do not see the columns of A), and
// r̂ = L̂⁻¹ D^{-1/2} r with it, by one pass over S (SymmetricGaussSeidel::first_residual);
// then, unless r already meets the tolerance, p = r̂ and r̂ᵀr̂.  (Every loop over the
// vectors is shared among the threads, an entry to a thread: the set-up's passes, on one
// thread, kept the second one waiting for a tenth of the impact window's time at n = 320.)
// Returns max_{i ∉ A} |r_i| / S_ii.
double MaskedCG::set_up_on_all_rows(const std::vector<char>& held, const Eigen::VectorXd& b, Eigen::VectorXd& y,
                                    double tol) {
  const int n = sgs_.size();
  for (Eigen::VectorXd* v : {&r_, &r_hat_, &p_, &t_, &w_, &q_}) v->resize(n);
  zero_outside_ = false;  // (written on every row below)
  const bool threaded = 2L * n >= kParallelWork;
  const Eigen::VectorXd& sqrt_d = sgs_.sqrt_diagonal();
#pragma omp parallel for schedule(static) if (threaded)
  for (int i = 0; i < n; ++i) {
    if (held[i]) y[i] = b[i];
    t_[i] = held[i] ? 0.0 : sqrt_d[i] * y[i];  // ŷ = D^{1/2} y on I
  }
  sgs_.first_residual(held, b.data(), t_.data(), w_.data(), r_hat_.data(), r_.data());
  const double scaled = scaled_max(r_, D_);
  if (!(scaled > tol)) return scaled;
  rr_ = dot(r_hat_, r_hat_);
#pragma omp parallel for schedule(static) if (threaded)
  for (int i = 0; i < n; ++i) p_[i] = r_hat_[i];
  return scaled;
}

// The same on the free rows I alone, when most rows are held: the work vectors vanish
// on A, which the sweeps read and never write, so only the rows the last solve on free
// rows wrote are cleared, and the set-up costs O(|I|) besides y_A = b_A.  (Over all
// rows, the set-up and the final residual were 25 passes over the vectors: with 0.6 %
// of a 640 × 640 grid's rows free, a solve of two iterations took 4.4 ms, 1.2 on the
// free rows alone.)
double MaskedCG::set_up_on_free_rows(const std::vector<char>& held, const Eigen::VectorXd& b, Eigen::VectorXd& y,
                                     double tol) {
  const int n = sgs_.size();
  if (zero_outside_ && r_.size() == n) {
    for (int i : written_)
      for (Eigen::VectorXd* v : {&r_, &r_hat_, &p_, &t_, &w_, &q_}) (*v)[i] = 0.0;
  } else {
    for (Eigen::VectorXd* v : {&r_, &r_hat_, &p_, &t_, &w_, &q_}) v->setZero(n);
  }
  zero_outside_ = true;
  written_ = free_;
#pragma omp parallel for schedule(static) if (2L * n >= kParallelWork)
  for (int i = 0; i < n; ++i)
    if (held[i]) y[i] = b[i];
  const Eigen::VectorXd& sqrt_d = sgs_.sqrt_diagonal();
  for (int i : free_) t_[i] = sqrt_d[i] * y[i];  // ŷ = D^{1/2} y on I
  free_rows_ = sgs_.free_rows(free_);
  sgs_.first_residual(free_rows_, b.data(), t_.data(), w_.data(), r_hat_.data(), r_.data());
  const double scaled = scaled_max(free_, r_, D_);
  if (!(scaled > tol)) return scaled;
  rr_ = dot_on(ListedRows{free_, int(free_.size())}, r_hat_.data(), r_hat_.data(), block_rr_);
  for (int i : free_) p_[i] = r_hat_[i];
  return scaled;
}

MaskedCGResult MaskedCG::solve(const std::vector<char>& held, const Eigen::VectorXd& b, Eigen::VectorXd& y,
                               double tol, int max_iterations, bool resume) {
  const int n = sgs_.size();
  const Eigen::VectorXd& sqrt_d = sgs_.sqrt_diagonal();
  MaskedCGResult result;
  // r = D^{1/2} L̂ r̂, from CG's r̂ (into r_; t_ is scratch)
  auto unprecondition = [&]() {
    if (compact_) {
      sgs_.multiply_lower(free_rows_, r_hat_.data(), t_.data());
      for (int i : free_) r_[i] = t_[i] * sqrt_d[i];
      return scaled_max(free_, r_, D_);
    }
    sgs_.multiply_lower(held, r_hat_.data(), t_.data());
#pragma omp parallel for schedule(static) if (2 * n >= kParallelWork)
    for (int i = 0; i < n; ++i) r_[i] = t_[i] * sqrt_d[i];
    return scaled_max(r_, D_);
  };

  // The iteration's loops on the rows it visits: all, or the free ones (compact_).
  auto on_rows = [&](auto&& loop) { return compact_ ? loop(ListedRows{free_, int(free_.size())}) : loop(AllRows{n}); };

  const bool resuming = resume && resumable_ && y.size() == n;
  resumable_ = false;  // until this solve converges
  if (resuming) {
    // the interrupted iteration's next direction
    result.scaled_residual = last_scaled_;
    if (!(last_scaled_ > tol)) {
      result.converged = true;
      return result;
    }
    on_rows([&](auto I) { next_direction(I, r_hat_.data(), rr_next_ / rr_, p_.data()); });
    rr_ = rr_next_;
  } else {
    if (y.size() != n) y = Eigen::VectorXd::Zero(n);
    // Most rows held (resting contact, a chattering contact zone): the iterations visit
    // the free rows alone.  Every vector of the iteration is 0 on the held rows, and the
    // whole-vector sweeps spent most of their time writing those zeros (the resting
    // membrane at n = 160, 97 % of the unknowns held: 20.2 → 18.5 ms a step).
    compact_ = 2 * std::count(held.begin(), held.end(), 0) < n;
    if (compact_) free_ = indices_where(n, [&](int i) { return !held[i]; });
    result.scaled_residual = compact_ ? set_up_on_free_rows(held, b, y, tol) : set_up_on_all_rows(held, b, y, tol);
    if (!(result.scaled_residual > tol)) {
      result.converged = std::isfinite(result.scaled_residual);
      return result;
    }
  }
  for (int k = 1; k <= max_iterations; ++k) {
    double pq;
    if (compact_) {
      sgs_.apply(free_rows_, p_.data(), t_.data(), w_.data(), q_.data());
      pq = dot_on(ListedRows{free_, int(free_.size())}, p_.data(), q_.data(), block_rr_);
    } else {
      pq = sgs_.apply(held, p_.data(), t_.data(), w_.data(), q_.data());
    }
    const double alpha = rr_ / pq;
    const Sweep sweep = on_rows([&](auto I) {
      return update(I, alpha, t_.data(), q_.data(), inverse_sqrt_D_.data(), y.data(), r_hat_.data(), block_rr_);
    });
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
    on_rows([&](auto I) { next_direction(I, r_hat_.data(), sweep.rr / rr_, p_.data()); });
    rr_ = sweep.rr;
  }
  result.scaled_residual = unprecondition();
  return result;
}

}  // namespace cdyn
