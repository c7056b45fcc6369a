// explicit_reduced_system.cpp — S̃ X = b̃ for an explicit S by a kept CHOLMOD factor,
// row updates (Davis & Hager 2005) and masked CG; see explicit_reduced_system.hpp.  How
// each way to a new active set is priced: explicit_reduced_system_pricing.cpp.
#include "cdyn/qp/pdas/explicit_reduced_system.hpp"

#include <algorithm>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/linalg/threads.hpp"

namespace cdyn {

namespace {

// max |i − j| over M's entries (i, j): a column j holds rows within j ± the bandwidth.
int bandwidth(const SparseMatrix& M) {
  const int* outer = M.outerIndexPtr();
  const int* inner = M.innerIndexPtr();
  int band = 0;
  for (int j = 0; j < M.outerSize(); ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) band = std::max(band, std::abs(inner[k] - j));
  return band;
}

// True if every column j < n of M stores its diagonal entry.
bool has_diagonal(const SparseMatrix& M, int n) {
  for (int j = 0; j < n; ++j) {
    bool found = false;
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) found = found || it.row() == j;
    if (!found) return false;
  }
  return true;
}

}  // namespace

ExplicitReducedSystem::ExplicitReducedSystem(const QPOptions& options, PDASCounters& counters)
    : opt_(options), counters_(counters) {}

void ExplicitReducedSystem::prepare(const BoundQP& qp, bool new_matrices) {
  n_ = qp.size();
  // calls_ counts time steps: a set that served the two solves of one discrete gradient
  // step and the next step has not settled more than one that served two midpoint steps
  // (counted by solves, the discrete gradient's chattering membrane brought the factor
  // to sets that the next step left: N_X = 40, dt = 0.01, 2.02 → 1.83 its midpoint's
  // time, ten interleaved runs)
  if (!same_step_next_) ++calls_;
  capacitance_has_r_ = false;  // (a new QP: its r)
  by_factor_ = same_step_next_ && round_off_next_;
  same_step_next_ = round_off_next_ = false;
  const bool ready = chol_.factorized() || (opt_.pdas_cg_only && cg_);
  if (!new_matrices && ready) return;
  if (same_matrix(qp.S, S_) && ready) return;
  S_ = qp.S;
  S_.makeCompressed();
  if (!has_diagonal(S_, n_)) throw NumericalError("pdas: S has a zero diagonal entry: it is not positive definite");
  bandwidth_ = bandwidth(S_);
  if (opt_.pdas_cg_only) {
    // No factor: CG on S̃ for every held set (a breakdown of CG, pᵀSp ≤ 0, is reported
    // as non-convergence by solve_tilde).
    cg_.reset();
    cg_.emplace(S_);
    way_ = Way::Cg;
    cg_failed_ = false;
    cg_held_.assign(n_, 0);
    return;
  }
  if (!chol_.analyzed_for(S_)) {
    chol_.analyze(S_);
    ++counters_.analyses;
    update_flops_ = 0.0;
    updates_measured_ = 0;
  }
  S_tilde_ = S_;
  chol_.forget_kept();
  capacitance_.clear();
  factorize_counted(chol_, S_, "S is not positive definite (CHOLMOD: the factorization breaks down", counters_);
  whole_in_chol_ = true;
  take_whole_factor();
  cg_failed_ = false;
  cg_.reset();
  if (opt_.pdas_cg_iterations > 0) cg_.emplace(S_);
}

void ExplicitReducedSystem::refactorize(const HeldSet& held) {
  const auto n_free = std::count(held.begin(), held.end(), 0);
  block_mode_ = factorizes_free_block(n_free);
  if (block_mode_) {
    block_.make(S_, held, chol_, counters_);
  } else {
    leave_whole_factor();
    replace_held_by_identity(S_, held, S_tilde_);
    factorize_counted(chol_, S_tilde_, "the reduced matrix S_II is not positive definite (breakdown", counters_);
  }
  factor_made_for(held);
}

// The factor is a fresh one of `held`: no row update on it, and no CG since (CG mode off).
void ExplicitReducedSystem::factor_made_for(const HeldSet& held) {
  capacitance_has_r_ = false;  // (L⁻¹ P r was another factor's)
  factor_held_ = held;
  updates_since_factorization_ = 0;
  way_ = Way::Factor;
  cg_since_sync_ = 0;
}

// chol_ is about to hold another factor than S's own: S's is kept (a copy) the first time.
void ExplicitReducedSystem::leave_whole_factor() {
  capacitance_has_r_ = false;
  if (whole_in_chol_ && !chol_.has_kept()) chol_.keep();
  whole_in_chol_ = false;
}

// The factor becomes S's own, that of the empty held set: chol_'s as it is, or a copy of
// the kept one (entries of L copied once, a quarter of a solve's reads and writes; its
// time is counted with the row updates', the other way the factor is moved to a set).
void ExplicitReducedSystem::take_whole_factor() {
  if (!whole_in_chol_) {
    ScopeTimer timer(counters_.row_update_s);
    chol_.use_kept();
    whole_in_chol_ = true;
  }
  block_mode_ = false;
  factor_made_for(HeldSet(n_, 0));
}

// Brings the factor to `held` (row updates or a refactorization), leaving CG mode.
void ExplicitReducedSystem::sync_factor(const HeldSet& held) {
  way_ = Way::Factor;
  std::vector<int> to_delete, to_add;
  for (int i = 0; i < n_; ++i)
    if (held[i] != factor_held_[i]) (held[i] ? to_delete : to_add).push_back(i);
  const int changes = static_cast<int>(to_delete.size() + to_add.size());
  if (changes == 0) return;
  if (block_mode_) {
    if (!block_.updates_pay(factor_held_, held, update_limit())) return refactorize(held);  // a new block
    ScopeTimer timer(counters_.row_update_s);
    if (!block_.update(to_delete, to_add)) return refactorize(held);  // round-off: start afresh
    factor_held_ = held;
  } else {
    if (changes > update_limit() || refactorization_pays(changes)) return refactorize(held);
    ScopeTimer timer(counters_.row_update_s);
    leave_whole_factor();
    if (!update_held(chol_, S_, factor_held_, to_delete, to_add, update_flops_)) return refactorize(held);
    updates_measured_ += changes;
  }
  counters_.row_updates += changes;
  updates_since_factorization_ += changes;
  cg_since_sync_ = 0;
}

void ExplicitReducedSystem::set_held(const HeldSet& held, bool fresh) {
  track_run(held);
  if (opt_.pdas_cg_only) {
    cg_held_ = held;
    return;
  }
  if (fresh || !chol_.factorized()) return refactorize(held);
  if (held == factor_held_) {
    way_ = Way::Factor;
    return;
  }
  // Nothing held, and S's own factor at hand: one solve with it.  (The body has lifted
  // off: the chattering membrane between its contacts, the falling one before impact.)
  if ((whole_in_chol_ || chol_.has_kept()) && std::none_of(held.begin(), held.end(), [](char h) { return h != 0; }))
    return take_whole_factor();
  // A few held, S's factor in chol_: that factor and their capacitance matrix.
  if (capacitance_pays(held)) {
    way_ = Way::Capacitance;
    return;
  }
  if (cg_ && !cg_failed_ && !by_factor_ && !resync_due(held) && cg_pays(held)) {
    if (!(way_ == Way::Cg && held == cg_held_))
      cg_mode_uses_ = 1;
    else if (cg_held_call_ != calls_)
      ++cg_mode_uses_;
    cg_held_call_ = calls_;
    way_ = Way::Cg;  // the factor stays as it is; solve_tilde runs CG
    cg_held_ = held;
    return;
  }
  sync_factor(held);
}

// Solves S̃ y = b the way set_held chose: by CG (stopping at the Jacobi-scaled residual
// cg_tol, masked_cg.hpp), by the capacitance matrix, or by the factor (to round-off).
const Eigen::VectorXd& ExplicitReducedSystem::solve_tilde(const Eigen::VectorXd& b, double cg_tol) {
  ++counters_.solves;
  last_cg_residual_ = 0.0;
  const bool resume = resume_cg_ && last_by_cg_;
  resume_cg_ = last_by_cg_ = false;
  if (way_ == Way::Capacitance) {
    ScopeTimer timer(counters_.solve_s);
    ++counters_.capacitance_solves;
    capacitance_.solve(chol_, b, y_last_);
    return y_last_;
  }
  if (way_ == Way::Cg) {
    // From the last solution (the previous PDAS iterate or step: the systems differ in a
    // few rows and the right-hand side by O(dt)).
    // (y_last_ is iterated in place: CG's answer, or overwritten by the factor's below)
    Eigen::VectorXd& y = y_last_;
    MaskedCGResult run;
    const int cap = opt_.pdas_cg_only ? std::max(opt_.pdas_cg_iterations, 2000) : opt_.pdas_cg_iterations;
    {
      ScopeTimer timer(counters_.cg_s);
      run = cg_->solve(cg_held_, b, y, cg_tol, cap, resume);
    }
    counters_.cg_iterations += run.iterations;
    cg_since_sync_ += run.iterations;
    if (run.converged) {
      ++counters_.cg_solves;
      last_cg_residual_ = run.scaled_residual;
      last_by_cg_ = true;
      return y;
    }
    if (opt_.pdas_cg_only)
      throw NumericalError("pdas: CG on the reduced system did not converge in " + std::to_string(run.iterations) +
                           " iterations (scaled residual " + std::to_string(run.scaled_residual) +
                           "): the step matrix is not well conditioned enough for the CG path (use the factor)");
    cg_failed_ = true;  // S̃ not well conditioned enough: the factor from now on
    sync_factor(cg_held_);
  }
  ScopeTimer timer(counters_.solve_s);
  y_last_ = block_mode_ ? block_.solve(b) : chol_.solve(b);
  return y_last_;
}

Eigen::VectorXd ExplicitReducedSystem::solve_fixed(const BoundQP& qp, const HeldSet& held,
                                                   const Eigen::VectorXd& value, double tol) {
  set_held(held);  // (a resumed solve's set too: the CG measured so far may now price the factor lower)
  if (way_ == Way::Capacitance) return solve_by_capacitance(qp, value);
  if (!(resume_cg_ && last_by_cg_)) build_rhs(qp, held, value);  // (resumed: b̃ is the last one)
  const Eigen::VectorXd& y = solve_tilde(b_, tol);
  Eigen::VectorXd X(n_);  // y with X_A = value_A exactly
#pragma omp parallel for schedule(static) if (2L * n_ >= kParallelWork)
  for (int i = 0; i < n_; ++i) X[i] = held[i] ? value[i] : y[i];
  return X;
}

// The minimizer with X_A = value_A by S's factor and the capacitance matrix, written
// with the QP's r (capacitance_solve.hpp, solve_held): the forward sweep L⁻¹ P r is made
// at the QP's first such iterate and serves the others, which cost a backward sweep each.
// (The chattering membrane's few held unknowns switch at most steps: a second iterate
// with the same r.)
Eigen::VectorXd ExplicitReducedSystem::solve_by_capacitance(const BoundQP& qp, const Eigen::VectorXd& value) {
  ++counters_.solves;
  ++counters_.capacitance_solves;
  last_cg_residual_ = 0.0;
  resume_cg_ = last_by_cg_ = false;
  ScopeTimer timer(counters_.solve_s);
  if (!capacitance_has_r_) {
    capacitance_.set_rhs(chol_, qp.r);
    capacitance_has_r_ = true;
  }
  capacitance_.solve_held(chol_, value, y_last_);
  return y_last_;
}

// b_ = b̃, the right-hand side of S̃ X = b̃ for `held` and the held values `value`.
void ExplicitReducedSystem::build_rhs(const BoundQP& qp, const HeldSet& held, const Eigen::VectorXd& value) {
  // b̃_I = r_I − S_IA X_A, b̃_A = X_A.  S being symmetric, b̃_i for a free i is also a
  // gather over column i, its terms in the same order (j increasing) as the scatter's
  // over the held columns j (the same sum where S is symmetric to the bit): whichever
  // reads fewer columns — the gather when most unknowns are held (resting contact:
  // about 99 %, where the scatter over S's held columns was a quarter of pdas's own
  // time at n = 640).
  // (b̃ starts as r on I and X_A on A, in one pass; the sums below touch only I)
  Eigen::VectorXd& b = b_;
  b.resize(n_);
  const auto n_held = std::count_if(held.begin(), held.end(), [](char h) { return h != 0; });
#pragma omp parallel for schedule(static) if (2L * n_ >= kParallelWork)
  for (int i = 0; i < n_; ++i) b[i] = held[i] ? value[i] : qp.r[i];
  const int* outer = S_.outerIndexPtr();
  const int* inner = S_.innerIndexPtr();
  const double* s = S_.valuePtr();
  if (2 * n_held > n_) {
#pragma omp parallel for schedule(static) if (S_.nonZeros() >= kParallelWork)
    for (int i = 0; i < n_; ++i)
      if (!held[i])
        for (int k = outer[i]; k < outer[i + 1]; ++k)
          if (held[inner[k]]) b[i] -= s[k] * value[inner[k]];
  } else {
    // The scatter, its rows cut into one range per thread: each part walks the held
    // columns that can reach its rows (those within S's bandwidth of them: a mesh's
    // numbering keeps it small) and updates its own rows only, so every b_i gets its
    // terms in the order of one thread (j increasing).  (On one thread this loop was a
    // tenth of the main thread's time in the impact window at n = 320, where the other
    // thread waited for it.)
    const int parts = 5L * n_held >= kParallelWork ? thread_count() : 1;
#pragma omp parallel for schedule(static, 1) if (parts > 1)
    for (int part = 0; part < parts; ++part) {
      const int lo = static_cast<int>(long(n_) * part / parts), hi = static_cast<int>(long(n_) * (part + 1) / parts);
      const int first = std::max(0, lo - bandwidth_), last = static_cast<int>(std::min<long>(n_, long(hi) + bandwidth_));
      for (int j = first; j < last; ++j) {
        if (!held[j]) continue;
        for (int k = outer[j]; k < outer[j + 1]; ++k)
          if (inner[k] >= lo && inner[k] < hi && !held[inner[k]]) b[inner[k]] -= s[k] * value[j];
      }
    }
  }
}

// After a CG solve the free rows of λ are CG's residual with the sign changed: its b̃_I
// is r_I − S_IA X_A, so (S X − r)_I = −(b̃ − S̃X)_I; only the held rows need S, one
// column each (S symmetric: column i is row i), |A| columns instead of all n.  After a
// solve with the factor, the whole product.
// From the previous iterate of the same QP, the rows held at both change only through
// the columns where X moved: λ_i += Σ_j S_ij (X_j − X⁰_j), over those columns in
// increasing order (a scatter, on one thread).  Where few moved — the free unknowns of
// resting or chattering contact, most of S's rows held — that reads their columns
// instead of every held row.  Each λ_i then carries the round-off of its updates, a few
// ε ‖S_i‖ ‖X‖ like the product's own; the other rows are gathered as the product does.
void ExplicitReducedSystem::reaction(const BoundQP& qp, const QuadraticForm& form, const Eigen::VectorXd& X,
                                     const HeldSet& held, Eigen::VectorXd& lam, const Iterate* previous) const {
  // (the scatter reads a column for each moved unknown on one thread, the whole product
  // every row on all of them: it pays for up to a quarter of the columns.  X moves on the
  // free rows, and on a held row only if its bound changed.)
  const auto few = [&](std::size_t count) { return 4 * count <= static_cast<std::size_t>(n_); };
  std::vector<int> moved;
  bool update = previous && lam.size() == n_ && previous->X.size() == n_ && few(std::count(held.begin(), held.end(), 0));
  if (update) {
    moved = indices_where(n_, [&](int j) { return X[j] != previous->X[j]; });
    update = few(moved.size());
  }
  if (!update) previous = nullptr;
  if (!previous && !last_by_cg_) {
    lam = form.gradient(X);
    return;
  }
  const int* outer = S_.outerIndexPtr();
  const int* inner = S_.innerIndexPtr();
  const double* s = S_.valuePtr();
  if (previous) {
    const HeldSet& held0 = previous->held;
    for (int j : moved) {
      const double dx = X[j] - previous->X[j];
      for (int k = outer[j]; k < outer[j + 1]; ++k)
        if (held[inner[k]] && held0[inner[k]]) lam[inner[k]] += s[k] * dx;
    }
  } else {
    lam.resize(n_);
  }
  const double* residual = last_by_cg_ ? cg_->residual().data() : nullptr;
#pragma omp parallel for schedule(static) if (S_.nonZeros() >= kParallelWork)
  for (int i = 0; i < n_; ++i) {
    if (previous && held[i] && previous->held[i]) continue;
    if (!held[i] && residual) {
      lam[i] = -residual[i];
      continue;
    }
    double sum = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) sum += s[k] * X[inner[k]];
    lam[i] = sum - qp.r[i];
  }
}

Eigen::VectorXd ExplicitReducedSystem::solve_correction(const Eigen::VectorXd& b, double tol) {
  y_last_.setZero();  // a correction or a direction: CG from 0
  return solve_tilde(b, tol);
}

}  // namespace cdyn
