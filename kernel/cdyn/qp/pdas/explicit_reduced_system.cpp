// explicit_reduced_system.cpp — S̃ X = b̃ for an explicit S by a kept CHOLMOD factor,
// row updates (Davis & Hager 2005) and masked CG; see explicit_reduced_system.hpp.
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
    cg_mode_ = true;
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
  factorize_counted(chol_, S_, "S is not positive definite (CHOLMOD: the factorization breaks down", counters_);
  whole_in_chol_ = true;
  take_whole_factor();
  cg_failed_ = false;
  cg_.reset();
  if (opt_.pdas_cg_iterations > 0) cg_.emplace(S_);  // (references the member S_)
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
  factor_held_ = held;
  updates_since_factorization_ = 0;
  cg_mode_ = false;
  cg_since_sync_ = 0;
}

// chol_ is about to hold another factor than S's own: S's is kept (a copy) the first time.
void ExplicitReducedSystem::leave_whole_factor() {
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
  cg_mode_ = false;
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

// Row updates beyond this many changes cost more than a factorization: measured on the
// obstacle (docs/performance.md), one row update costs 1/300 to 1/600 of a
// factorization from 6k to 100k unknowns, and the break-even grows with the size.
int ExplicitReducedSystem::update_limit() const {
  return opt_.pdas_update_limit >= 0 ? opt_.pdas_update_limit : std::max(300, n_ / 100);
}

// Whether a fresh factorization of S̃ costs less than `changes` row updates at their
// mean flops so far: under half their flops (the analysis's count; the margin because a
// refactorization also copies the analysis and rebuilds the supernodes: at n = 80 on the
// membrane without CG, refactorizations chosen at 1.3× fewer flops made the steps 8 %
// slower).  On a small or nearly banded S — the thin beam's 404 unknowns: 1.4e4 flops a
// factorization — it is the cheaper way at any number of changes.
bool ExplicitReducedSystem::refactorization_pays(int changes) const {
  return updates_measured_ > 0 && 2.0 * chol_.factorization_flops() < changes * (update_flops_ / updates_measured_);
}

// Whether bringing the factor (S̃'s, not a free block's) to a set `changes` unknowns away
// is priced as a refactorization rather than as that many row updates: beyond
// update_limit(), where a refactorization pays, and before any row update is measured
// (then a refactorization's count stands in for them).  (sync_factor itself does row
// updates in that last case, to measure them.)  For cg_pays and resync_pays.
bool ExplicitReducedSystem::priced_as_refactorization(int changes) const {
  return changes > update_limit() || updates_measured_ == 0 || refactorization_pays(changes);
}

// Whether the factor should now be brought to `held` although CG would do: when the
// active set has settled — used by the last kSettled calls in a row (while the contact
// zone chatters, each set serves at most two: the last solves of a step and the first of
// the next) — so that the coming steps are one forward/back solve each again; or after
// pdas_cg_resync CG iterations since the last sync, if set.
bool ExplicitReducedSystem::resync_due(const HeldSet& held) const {
  if (opt_.pdas_cg_resync >= 0 && cg_since_sync_ >= opt_.pdas_cg_resync) return true;
  return cg_mode_ && held == cg_held_ && cg_held_call_ != calls_ && cg_mode_uses_ + 1 >= kSettled &&
         resync_pays(held);
}

// Whether bringing the factor to a settled set costs less than the CG it saves: each
// call the set serves from now on costs one solve with the factor instead of a CG pair
// (a loose solve and its tight resumption: twice the mean CG solve), and the settled
// sets seen so far served `uses` such calls on average.  A refactorization of the
// condensed P1+/P0 membrane (n = 160) costs 22 forward/back solves' flops, or 110 CG
// iterations; a chattering contact zone that settles for two or three steps at a time
// spent 3.7 ms a step on them: 1.78 times the linear step, 1.42 with this rule
// (docs/performance.md, "Contact in every regime").  Until a settled set has
// ended, and for resting contact (a small free block, cheap to factorize and to solve
// with), it pays.  Flop counts, not clocks: a run repeats exactly.
bool ExplicitReducedSystem::resync_pays(const HeldSet& held) const {
  if (settled_runs_ == 0 || counters_.cg_solves == 0) return true;
  const double uses = settled_uses_ / settled_runs_;
  const double cg_call = 2.0 * double(counters_.cg_iterations) / counters_.cg_solves * cg_iteration_flops();
  const Sync sync = sync_cost(held);
  return uses * (cg_call - sync.solve_flops) > sync.flops;
}

// What sync_factor(held) will do, in flops, and the flops of a solve it leaves: row
// updates at their mean cost so far, or a refactorization (priced_as_refactorization) —
// of the free block S_II when it leaves at most pdas_free_block of the unknowns free.
// A new free block's flops are estimated from S's: a fraction f of the unknowns of a
// 2D-like graph, f^1.5 of the factorization (nested dissection's N^1.5) and f of the
// solve.  (Measured where it matters, the resting membrane's reconstruction at n = 640:
// 1.2 % of the unknowns free, a block factorization 57 ms against CG's 63 ms a solve,
// where S's whole factorization costs 1.8 s.)
ExplicitReducedSystem::Sync ExplicitReducedSystem::sync_cost(const HeldSet& held) const {
  int changes = 0, n_free = 0;
  for (int i = 0; i < n_; ++i) {
    changes += held[i] != factor_held_[i];
    n_free += !held[i];
  }
  const bool block = factorizes_free_block(n_free);
  if (block_mode_ && block)  // (before any row update on a block is measured, priced as a new block)
    return {block_.updates_measured() && block_.updates_pay(factor_held_, held, update_limit())
                ? changes * block_.update_flops()
                : block_.factorization_flops(),
            block_.solve_flops()};
  // From a free block, a set that leaves more unknowns free (the resting body lifts off)
  // is never row updates of S̃'s factor but its refactorization, priced below.  (Priced
  // as the block's own, a few hundred unknowns, such a jump was always synced: the
  // chattering membrane's lift-off made two factorizations of S̃ where CG was cheaper;
  // without them its P1+/P0 step 16.7, 16.2 → 14.8, 14.5 ms over 100 steps, n = 160.)
  if (!block_mode_ && !priced_as_refactorization(changes))
    return {changes * (update_flops_ / updates_measured_), chol_.solve_flops()};
  const double f = double(n_free) / n_;
  return {chol_.factorization_flops() * (block ? std::pow(f, 1.5) : 1.0), chol_.solve_flops() * (block ? f : 1.0)};
}

// Counts the calls in a row that use one held set (resync_pays).
void ExplicitReducedSystem::track_run(const HeldSet& held) {
  if (held != run_held_) {
    if (run_uses_ >= kSettled) {
      ++settled_runs_;
      settled_uses_ += run_uses_ - kSettled + 1;
    }
    run_held_ = held;
    run_uses_ = 1;
  } else if (run_call_ != calls_) {
    ++run_uses_;
  }
  run_call_ = calls_;
}

// A CG iteration's flops: the product with S (read once, Eisenstat's trick: masked_cg.hpp)
// and the five vector updates.
double ExplicitReducedSystem::cg_iteration_flops() const { return 2.0 * double(S_.nonZeros()) + 12.0 * n_; }

// Whether a CG solve is expected to cost less than bringing the factor to `held`.
// Bringing the factor there is what sync_factor does (sync_cost): beyond update_limit()
// changes, or where it pays (refactorization_pays), a refactorization — of the free
// block alone when most unknowns are held — whose flops the analysis counts; otherwise
// one row update per changed unknown, whose cost CHOLMOD counts (modfl, mean over the
// updates done so far on this pattern; before any is measured, a refactorization's
// count stands in for them).  That is weighed against a CG solve of
// (mean iterations so far) × (2 nnz(S) + 12 n) flops: the product with S and the five
// vector updates of an iteration.  All are sparse loops near memory speed, so flops
// compare their times to within a small factor (docs/performance.md (a): at n = 80
// small changes go to row updates, at n = 160 the contact jumps go to CG; on the thin
// beam a factorization costs 1.4e4 flops, a CG iteration 1.6e4, and CG took 20–30
// iterations).  The first new set goes to CG, whose iteration count no guess gets right
// (5 on the membrane at N_X = 40, dt = 0.01; 30 on the beam): a guess of 50 sent the
// membrane to row updates, 25 % slower a step.  Deterministic: flop counts, not clocks,
// so a run repeats exactly.
bool ExplicitReducedSystem::cg_pays(const HeldSet& held) const {
  if (opt_.pdas_cg_always) return true;
  const double iterations = counters_.cg_solves > 0 ? double(counters_.cg_iterations) / counters_.cg_solves : 50.0;
  const double cg_flops = iterations * cg_iteration_flops();
  // CG's own cost is measured first, but with a block factor, whose alternative is its row
  // updates or a new block (of about the same size), priced as it stands.
  if (!block_mode_ && counters_.cg_solves == 0) return true;
  return sync_cost(held).flops > cg_flops;
}

void ExplicitReducedSystem::set_held(const HeldSet& held, bool fresh) {
  track_run(held);
  if (opt_.pdas_cg_only) {
    cg_held_ = held;
    return;
  }
  if (fresh || !chol_.factorized()) return refactorize(held);
  if (held == factor_held_) {
    cg_mode_ = false;
    return;
  }
  // Nothing held, and S's own factor at hand: one solve with it.  (The body has lifted
  // off: the chattering membrane between its contacts, the falling one before impact.)
  if ((whole_in_chol_ || chol_.has_kept()) && std::none_of(held.begin(), held.end(), [](char h) { return h != 0; }))
    return take_whole_factor();
  if (cg_ && !cg_failed_ && !by_factor_ && !resync_due(held) && cg_pays(held)) {
    if (!(cg_mode_ && held == cg_held_))
      cg_mode_uses_ = 1;
    else if (cg_held_call_ != calls_)
      ++cg_mode_uses_;
    cg_held_call_ = calls_;
    cg_mode_ = true;  // the factor stays as it is; solve_tilde runs CG
    cg_held_ = held;
    return;
  }
  sync_factor(held);
}

// Solves S̃ y = b: by CG when the factor is not that of the held set (stopping at the
// Jacobi-scaled residual cg_tol, masked_cg.hpp), else by the factor (to round-off).
const Eigen::VectorXd& ExplicitReducedSystem::solve_tilde(const Eigen::VectorXd& b, double cg_tol) {
  ++counters_.solves;
  last_cg_residual_ = 0.0;
  const bool resume = resume_cg_ && last_by_cg_;
  resume_cg_ = last_by_cg_ = false;
  if (cg_mode_) {
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
  set_held(held);
  // b̃_I = r_I − S_IA X_A, b̃_A = X_A.  S being symmetric, b̃_i for a free i is also a
  // gather over column i, its terms in the same order (j increasing) as the scatter's
  // over the held columns j (the same sum where S is symmetric to the bit): whichever
  // reads fewer columns — the gather when most unknowns are held (resting contact:
  // about 99 %, where the scatter over S's held columns was a quarter of pdas's own
  // time at n = 640).
  // (b̃ starts as r on I and X_A on A, in one pass; the sums below touch only I)
  Eigen::VectorXd b(n_);
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
  const Eigen::VectorXd& y = solve_tilde(b, tol);
  Eigen::VectorXd X(n_);  // y with X_A = value_A exactly
#pragma omp parallel for schedule(static) if (2L * n_ >= kParallelWork)
  for (int i = 0; i < n_; ++i) X[i] = held[i] ? value[i] : y[i];
  return X;
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
