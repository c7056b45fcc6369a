// pdas.cpp — primal-dual active set (Hintermüller–Ito–Kunisch 2002) with a projected
// Newton fallback (Bertsekas 1982); see qp/pdas/pdas.hpp.
#include "cdyn/qp/pdas/pdas.hpp"

#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/masked_cg.hpp"

namespace cdyn {

namespace {

// Values of M with the rows and columns i < active.size() with active[i] replaced by the
// identity's, written into `out`, which has M's pattern.
void eliminate(const SparseMatrix& M, const std::vector<char>& active, SparseMatrix& out) {
  const int n = static_cast<int>(active.size());
  const int* outer = M.outerIndexPtr();
  const int* inner = M.innerIndexPtr();
  const double* m = M.valuePtr();
  double* v = out.valuePtr();
  for (int j = 0; j < M.outerSize(); ++j) {
    const bool aj = j < n && active[j];
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      const int i = inner[p];
      const bool ai = i < n && active[i];
      v[p] = (ai || aj) ? (i == j ? 1.0 : 0.0) : m[p];
    }
  }
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

// Adds the wall time of its scope to a counter (PDASSolver::Counters' *_s).
class ScopeTimer {
 public:
  explicit ScopeTimer(double& seconds) : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~ScopeTimer() { seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

// CG's stopping tolerance for a PDAS iterate that is not yet the solution, relative to
// the solution's scale (see cg_tolerance in PDASSolver::solve).
constexpr double kLooseSolve = 1e-4;

// State of an unknown: free, or held at its lower or upper bound.
constexpr signed char kFree = 0, kLower = -1, kUpper = 1;

}  // namespace

struct PDASSolver::Impl {
  QPOptions opt;
  Counters counters;
  CheckedMatrices checked;
  QuadraticForm form;

  // explicit S
  SparseMatrix S, S_tilde;            // the last S seen; S with the active set eliminated
  SparseCholesky chol;
  std::vector<char> factor_active;    // the active set chol currently factorizes
  int updates_since_factorization = 0;
  // CG on S̃ for an active set other than the factor's (see QPOptions::pdas_cg_iterations)
  bool cg_mode = false;               // solve_tilde uses CG with cg_active
  bool cg_failed = false;             // CG did not converge once for this S: not tried again
  std::vector<char> cg_active;
  int cg_since_sync = 0;              // CG iterations since the factor was last (re)made
  int cg_mode_uses = 0;               // calls of solve() in a row that used cg_active (resync_due)
  int calls = 0, cg_active_call = 0;  // solve() calls so far; the last that used cg_active
  std::optional<MaskedCG> cg;         // CG on S (its preconditioner, work vectors, last residual)
  Eigen::VectorXd y_last;             // the last solution of solve_tilde: CG's first guess
  double last_cg_residual = 0.0;      // CG's scaled residual in the last solve_tilde (0: by the factor)
  bool last_by_cg = false;            // the last solve_tilde was a converged CG solve
  bool resume_cg = false;             // the next solve_tilde repeats the last one at a smaller tol
  // What the two ways to a new active set have cost so far on this pattern (flops as
  // CHOLMOD counts them for a row update; CG iterations), for cg_pays().
  double update_flops = 0.0;
  int updates_measured = 0;

  // saddle form
  bool saddle = false;
  SaddleForm blocks;                  // the last blocks seen
  SparseMatrix K, K_tilde;            // [[A, c Bᵀ], [B, −C]] and its eliminated copy
  Eigen::UmfPackLU<SparseMatrix> lu;
  bool lu_factorized = false;
  std::vector<char> lu_active;

  int n = 0;

  // Makes the cached factorizations those of qp's matrix (analysis, PD check).
  void prepare(const BoundQP& qp, bool new_matrices) {
    form.set(qp, !new_matrices);
    n = qp.size();
    const bool was_saddle = saddle;
    saddle = qp.saddle.has_value();
    if (!new_matrices && saddle == was_saddle && (saddle ? lu_factorized : chol.factorized())) return;
    if (!saddle) {
      if (same_matrix(qp.S, S) && chol.factorized()) return;
      S = qp.S;
      S.makeCompressed();
      if (!has_diagonal(S, n))
        throw NumericalError("pdas: S has a zero diagonal entry: it is not positive definite");
      if (!chol.analyzed_for(S)) {
        chol.analyze(S);
        ++counters.analyses;
        update_flops = 0.0;
        updates_measured = 0;
      }
      S_tilde = S;
      factorize(S, "S is not positive definite (CHOLMOD: the factorization breaks down");
      factor_active.assign(n, 0);
      updates_since_factorization = 0;
      cg_mode = cg_failed = false;
      cg_since_sync = 0;
      cg.reset();
      if (opt.pdas_cg_iterations > 0) cg.emplace(S);  // (references the member S)
      return;
    }
    const SaddleForm& f = *qp.saddle;
    if (lu_factorized && f.c == blocks.c && same_matrix(f.A, blocks.A) && same_matrix(f.B, blocks.B) &&
        same_matrix(f.C, blocks.C))
      return;
    blocks = f;
    const int m = static_cast<int>(f.C.rows());
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(f.A.nonZeros() + 2 * f.B.nonZeros() + f.C.nonZeros() + n);
    for (int j = 0; j < n; ++j) t.emplace_back(j, j, 0.0);  // a stored diagonal for the identity rows
    for (int j = 0; j < n; ++j)
      for (SparseMatrix::InnerIterator it(f.A, j); it; ++it) t.emplace_back(it.row(), j, it.value());
    for (int j = 0; j < n; ++j)
      for (SparseMatrix::InnerIterator it(f.B, j); it; ++it) {
        t.emplace_back(n + it.row(), j, it.value());         // B
        t.emplace_back(j, n + it.row(), f.c * it.value());   // c Bᵀ
      }
    for (int j = 0; j < m; ++j)
      for (SparseMatrix::InnerIterator it(f.C, j); it; ++it) t.emplace_back(n + it.row(), n + j, -it.value());
    SparseMatrix Knew(n + m, n + m);
    Knew.setFromTriplets(t.begin(), t.end());
    Knew.makeCompressed();
    const bool same_pattern = same_matrix(Knew, K, false) && lu_factorized;
    K = std::move(Knew);
    K_tilde = K;
    if (!same_pattern) {
      lu.analyzePattern(K);
      ++counters.analyses;
      if (lu.info() != Eigen::Success)
        throw NumericalError("pdas: UMFPACK could not analyse the saddle matrix [[A, c B^T], [B, -C]]");
    }
    lu_factorized = false;
  }

  // A numeric factorization of `matrix` (timed, counted); NumericalError "pdas: <what> at
  // unknown i)" if CHOLMOD finds it not positive definite.
  void factorize(const SparseMatrix& matrix, const std::string& what) {
    ScopeTimer timer(counters.factorization_s);
    const int minor = chol.factorize(matrix);
    ++counters.factorizations;
    if (minor >= 0) throw NumericalError("pdas: " + what + " at unknown " + std::to_string(minor) + ")");
  }

  void refactorize(const std::vector<char>& active) {
    eliminate(S, active, S_tilde);
    factorize(S_tilde, "the reduced matrix S_II is not positive definite (breakdown");
    factor_active = active;
    updates_since_factorization = 0;
    cg_mode = false;
    cg_since_sync = 0;
  }

  // Brings the factor to `active` (row updates or a refactorization), leaving CG mode.
  void sync_factor(const std::vector<char>& active) {
    cg_mode = false;
    std::vector<int> to_delete, to_add;
    for (int i = 0; i < n; ++i)
      if (active[i] != factor_active[i]) (active[i] ? to_delete : to_add).push_back(i);
    const int changes = static_cast<int>(to_delete.size() + to_add.size());
    if (changes == 0) return;
    if (changes > update_limit()) return refactorize(active);
    ScopeTimer timer(counters.row_update_s);
    for (int i : to_delete) {
      chol.replace_by_identity(i);
      update_flops += chol.modification_flops();
      factor_active[i] = 1;
    }
    std::vector<char> keep(n);
    for (int i = 0; i < n; ++i) keep[i] = !factor_active[i];
    for (int i : to_add) {
      keep[i] = 1;
      if (!chol.restore(i, S, keep)) return refactorize(active);  // round-off: start afresh
      update_flops += chol.modification_flops();
      factor_active[i] = 0;
    }
    updates_measured += changes;
    counters.row_updates += changes;
    updates_since_factorization += changes;
    cg_since_sync = 0;
  }

  int update_limit() const { return opt.pdas_update_limit >= 0 ? opt.pdas_update_limit : std::max(300, n / 100); }

  double cg_iteration_flops() const { return 2.0 * double(S.nonZeros()) + 12.0 * n; }

  // Whether the factor should now be brought to the current active set although CG
  // would do: when the active set has settled — used by the last kSettled calls of
  // solve() in a row (while the contact zone chatters, each set serves at most two: the
  // last solves of a step and the first of the next) — so that the coming steps are one
  // forward/back solve each again; or after pdas_cg_resync CG iterations since the last
  // sync, if set.
  bool resync_due(const std::vector<char>& active) const {
    constexpr int kSettled = 3;
    if (opt.pdas_cg_resync >= 0 && cg_since_sync >= opt.pdas_cg_resync) return true;
    return cg_mode && active == cg_active && cg_active_call != calls && cg_mode_uses + 1 >= kSettled;
  }

  // Whether a CG solve is expected to cost less than bringing the factor to `active`.
  // Beyond update_limit() changes the alternative is a refactorization (≈ 30 solves):
  // CG.  Otherwise it is one row update per changed unknown, whose cost CHOLMOD counts
  // (modfl, mean over the updates done so far on this pattern), against a CG solve of
  // (mean iterations so far, 50 before any) × (2 nnz(S) + 12 n) flops: the product with
  // S and the five vector updates of an iteration.  Both are memory-bound sparse loops,
  // so flops compare their times to within a small factor (docs/performance.md (a):
  // at n = 80 small changes go to row updates, at n = 160 the contact jumps go to CG).
  // Before any update is measured, CG: the first resync measures one.  Deterministic:
  // flop counts, not clocks, so a run repeats exactly.
  bool cg_pays(const std::vector<char>& active) const {
    int changes = 0;
    for (int i = 0; i < n; ++i) changes += active[i] != factor_active[i];
    if (changes > update_limit() || updates_measured == 0) return true;
    const double iterations = counters.cg_solves > 0 ? double(counters.cg_iterations) / counters.cg_solves : 50.0;
    const double cg_flops = iterations * cg_iteration_flops();
    return changes * (update_flops / updates_measured) > cg_flops;
  }

  // Makes the factorization that of S̃ for this active set.
  void set_active(const std::vector<char>& active, bool fresh = false) {
    if (saddle) {
      if (lu_factorized && active == lu_active && !fresh) return;
      eliminate(K, active, K_tilde);
      lu.factorize(K_tilde);
      ++counters.factorizations;
      if (lu.info() != Eigen::Success)
        throw NumericalError("pdas: UMFPACK found the saddle matrix singular (is C positive definite and "
                             "A + c B^T C^-1 B positive definite?)");
      lu_factorized = true;
      lu_active = active;
      return;
    }
    if (fresh || !chol.factorized()) return refactorize(active);
    if (active == factor_active) {
      cg_mode = false;
      return;
    }
    if (cg && !cg_failed && !resync_due(active) && cg_pays(active)) {
      if (!(cg_mode && active == cg_active))
        cg_mode_uses = 1;
      else if (cg_active_call != calls)
        ++cg_mode_uses;
      cg_active_call = calls;
      cg_mode = true;  // the factor stays as it is; solve_tilde runs CG
      cg_active = active;
      return;
    }
    sync_factor(active);
  }

  // Solves S̃ y = top (explicit S), or K̃ [y; z] = [top; bottom] (saddle form).
  // CG (when the factor is not that of the active set) stops at the Jacobi-scaled
  // residual cg_tol (linalg/masked_cg.hpp); the factor solves to round-off.
  Eigen::VectorXd solve_tilde(const Eigen::VectorXd& top, const Eigen::VectorXd* bottom, double cg_tol) {
    ++counters.solves;
    last_cg_residual = 0.0;
    const bool resume = resume_cg && last_by_cg;
    resume_cg = last_by_cg = false;
    if (!saddle && cg_mode) {
      // From the last solution (the previous PDAS iterate or step: the systems differ in a
      // few rows and the right-hand side by O(dt)).
      Eigen::VectorXd y = y_last;
      MaskedCGResult run;
      {
        ScopeTimer timer(counters.cg_s);
        run = cg->solve(cg_active, top, y, cg_tol, opt.pdas_cg_iterations, resume);
      }
      counters.cg_iterations += run.iterations;
      cg_since_sync += run.iterations;
      if (run.converged) {
        ++counters.cg_solves;
        last_cg_residual = run.scaled_residual;
        last_by_cg = true;
        y_last = y;
        return y;
      }
      cg_failed = true;  // S̃ not well conditioned enough: the factor from now on
      sync_factor(cg_active);
    }
    if (!saddle) {
      ScopeTimer timer(counters.solve_s);
      y_last = chol.solve(top);
      return y_last;
    }
    const int m = static_cast<int>(K.rows()) - n;
    Eigen::VectorXd b(n + m);
    b.head(n) = top;
    if (bottom)
      b.tail(m) = *bottom;
    else
      b.tail(m).setZero();
    Eigen::VectorXd y = lu.solve(b);
    return y.head(n);
  }

  // λ = S X − r for the X that solve_fixed has just returned for `active`.  After a CG
  // solve the free rows are CG's residual with the sign changed: its b_I is
  // r_I − S_IA X_A, so (S X − r)_I = (S̃ y − b)_I; only the held rows need S, one column
  // each (S symmetric: column i is row i), |A| columns instead of all n.  After a solve
  // with the factor, or in saddle form, the whole product.
  Eigen::VectorXd reaction(const BoundQP& qp, const Eigen::VectorXd& X, const std::vector<char>& active) const {
    if (!last_by_cg) return form.apply(X) - qp.r;
    Eigen::VectorXd lam = -cg->residual();
    for (int i = 0; i < n; ++i)
      if (active[i]) {
        double sum = 0.0;
        for (SparseMatrix::InnerIterator it(S, i); it; ++it) sum += it.value() * X[it.row()];
        lam[i] = sum - qp.r[i];
      }
    return lam;
  }

  // The minimizer with X_i = value_i on the active unknowns: S_II X_I = r_I − S_IA X_A.
  Eigen::VectorXd solve_fixed(const BoundQP& qp, const std::vector<char>& active, const Eigen::VectorXd& value,
                              double cg_tol) {
    set_active(active);
    Eigen::VectorXd top = qp.r;
    Eigen::VectorXd bottom;
    if (!saddle) {
      for (int j = 0; j < n; ++j)
        if (active[j])
          for (SparseMatrix::InnerIterator it(S, j); it; ++it) top[it.row()] -= it.value() * value[j];
    } else {
      const SaddleForm& f = blocks;
      bottom = Eigen::VectorXd::Zero(f.C.rows());
      for (int j = 0; j < n; ++j)
        if (active[j]) {
          for (SparseMatrix::InnerIterator it(f.A, j); it; ++it) top[it.row()] -= it.value() * value[j];
          for (SparseMatrix::InnerIterator it(f.B, j); it; ++it) bottom[it.row()] -= it.value() * value[j];
        }
    }
    for (int j = 0; j < n; ++j)
      if (active[j]) top[j] = value[j];
    Eigen::VectorXd X = solve_tilde(top, saddle ? &bottom : nullptr, cg_tol);
    for (int j = 0; j < n; ++j)
      if (active[j]) X[j] = value[j];
    return X;
  }
};

PDASSolver::PDASSolver(const QPOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->opt = options;
  if (impl_->opt.max_iterations == 0) impl_->opt.max_iterations = 100;
}
PDASSolver::~PDASSolver() = default;
const PDASSolver::Counters& PDASSolver::counters() const { return impl_->counters; }

QPResult PDASSolver::solve(const BoundQP& qp, const QPResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  Impl& s = *impl_;
  const bool new_matrices = s.checked.check(qp, /*positive_definite=*/false, "pdas");  // PD: by its own factorization
  const QPOptions& opt = s.opt;
  const int n = qp.size();
  QPResult result;
  bool finished = false;  // result.reaction, kkt_residual, active already computed for result.X
  auto finish = [&](const std::string& detail) {
    if (!finished) finish_result(qp, s.form, opt.tol, result);
    if (result.X.size() == n) s.y_last = result.X;  // CG's first guess next time
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_failure("pdas", opt, result, detail);
    return result;
  };
  if (n == 0) {
    s.form.set(qp);
    result.X.resize(0);
    return finish("");
  }
  s.prepare(qp, new_matrices);
  ++s.calls;
  const Eigen::VectorXd& l = qp.lower;
  const Eigen::VectorXd& u = qp.upper;
  const Eigen::VectorXd& D = s.form.diagonal();
  for (int i = 0; i < n; ++i)
    if (!(D[i] > 0)) throw NumericalError("pdas: S has a non-positive diagonal entry: it is not positive definite");

  // The state (free / lower / upper) of every unknown, and the value it is held at.
  std::vector<signed char> state(n, kFree);
  auto bound_values = [&](const std::vector<signed char>& st, std::vector<char>& active, Eigen::VectorXd& value) {
    active.assign(n, 0);
    value = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i)
      if (st[i] != kFree) {
        active[i] = 1;
        value[i] = st[i] == kLower ? l[i] : u[i];
      }
  };
  // The PDAS rule: the next state from (X, λ).
  auto rule = [&](const Eigen::VectorXd& X, const Eigen::VectorXd& lam) {
    std::vector<signed char> st(n, kFree);
    for (int i = 0; i < n; ++i) {
      if (l[i] == u[i])
        st[i] = kLower;
      else if (std::isfinite(l[i]) && lam[i] + D[i] * (l[i] - X[i]) > 0)
        st[i] = kLower;
      else if (std::isfinite(u[i]) && lam[i] + D[i] * (u[i] - X[i]) < 0)
        st[i] = kUpper;
    }
    return st;
  };

  for (int i = 0; i < n; ++i)
    if (l[i] == u[i]) state[i] = kLower;  // fixed unknowns
  if (warm_start && warm_start->X.size() == n) {
    s.y_last = warm_start->X;  // CG's first guess
    // the previous active set, each unknown held at its nearer bound
    for (int i : warm_start->active) {
      if (i < 0 || i >= n || state[i] != kFree) continue;
      const double xi = warm_start->X[i];
      const bool has_l = std::isfinite(l[i]), has_u = std::isfinite(u[i]);
      if (has_l && (!has_u || std::abs(xi - l[i]) <= std::abs(xi - u[i])))
        state[i] = kLower;
      else if (has_u)
        state[i] = kUpper;
    }
  }

  // CG's tolerances on the Jacobi-scaled residual, in the units of kkt_residual (whose
  // scale max(‖X‖∞, ‖r/D‖∞) is bounded below by ‖r/D‖∞ and the held bound values; on
  // the free unknowns the natural residual is this scaled residual): half of tol for a
  // solution (the other half is margin for the drift of CG's updated residual from the
  // true one), and a loose one for an iterate that only has to point to the next active
  // set.  When the active set repeats on a loose solve, the same system is solved again
  // to the tight tolerance (CG from the loose solution) before the repeat is believed.
  const double r_scale = qp.r.cwiseQuotient(D).lpNorm<Eigen::Infinity>();
  auto cg_tolerance = [&](const Eigen::VectorXd& held_values, bool tight) {
    const double scale = std::max(r_scale, held_values.lpNorm<Eigen::Infinity>());
    return (tight ? 0.5 * opt.tol : std::max(0.5 * opt.tol, kLooseSolve)) * scale;
  };

  std::vector<char> active;
  Eigen::VectorXd value, X, lam;
  std::set<std::vector<signed char>> seen;
  bool cycled = false;
  bool refined_fresh = false;
  bool tight = false;
  int it = 0;
  while (it < opt.max_iterations) {
    ++it;
    bound_values(state, active, value);
    X = s.solve_fixed(qp, active, value, cg_tolerance(value, tight));
    lam = s.reaction(qp, X, active);  // CG's residual on the free unknowns
    const std::vector<signed char> next = rule(X, lam);
    result.iterations = it;
    if (next == state && !tight && s.last_cg_residual > cg_tolerance(value, true)) {
      tight = true;  // confirm on a tight solve: the same system, CG's iteration goes on
      s.resume_cg = true;
      continue;
    }
    tight = false;
    if (next == state) {
      // X is exact up to the linear solve: refine if the residual says it is not enough.
      // The reaction from the whole product: CG's updated residual has drifted by round-off.
      if (s.last_by_cg) lam = s.form.apply(X) - qp.r;
      result.X = X;
      result.reaction = lam;
      result.kkt_residual = kkt_residual(qp, X, lam, &D);
      result.active = active_set(qp, X, lam, D);
      result.converged = result.kkt_residual <= opt.tol;
      for (int k = 0; k < 2 && !result.converged; ++k) {
        Eigen::VectorXd top = -result.reaction;
        for (int i = 0; i < n; ++i)
          if (active[i]) top[i] = 0.0;
        Eigen::VectorXd zero;
        if (s.saddle) zero = Eigen::VectorXd::Zero(s.blocks.C.rows());
        s.y_last.setZero();  // a correction: CG from 0
        result.X += s.solve_tilde(top, s.saddle ? &zero : nullptr, cg_tolerance(value, true));
        finish_result(qp, s.form, opt.tol, result);
      }
      if (!result.converged && !refined_fresh && (s.saddle || s.cg_mode || s.updates_since_factorization > 0)) {
        refined_fresh = true;  // row updates (or CG) may have lost accuracy: refactorize, solve again
        s.set_active(active, true);
        continue;
      }
      finished = true;
      return finish("active set repeated but the residual stays above tol: S is ill-conditioned");
    }
    if (kkt_residual(qp, X, lam, &D) <= opt.tol) {
      // degenerate unknowns (λ_i ≈ 0 at the bound) may still switch: X is good if the
      // residual with the whole product says so too (finish recomputes λ that way)
      result.X = X;
      finish_result(qp, s.form, opt.tol, result);
      finished = result.converged;
      if (finished) return finish("");
    }
    if (seen.count(next)) {
      cycled = true;
      break;
    }
    seen.insert(state);
    state = next;
  }
  if (!cycled) {
    result.X = X;
    return finish("no convergence of the active set");
  }

  // ----- projected Newton (Bertsekas 1982) from the projection of the current X -----
  for (int i = 0; i < n; ++i) X[i] = std::clamp(X[i], l[i], u[i]);
  const double eps_bar = std::max(X.lpNorm<Eigen::Infinity>(), qp.r.cwiseQuotient(D).lpNorm<Eigen::Infinity>());
  const double sigma = 1e-4;
  while (it < opt.max_iterations) {
    ++it;
    ++s.counters.damped_iterations;
    result.iterations = it;
    lam = s.form.apply(X) - qp.r;
    if (kkt_residual(qp, X, lam, &D) <= opt.tol) {
      result.X = X;
      return finish("");
    }
    const double eps = std::min(eps_bar, natural_residual(qp, X, lam, D).lpNorm<Eigen::Infinity>());
    active.assign(n, 0);
    for (int i = 0; i < n; ++i)
      active[i] = l[i] == u[i] || (X[i] <= l[i] + eps && lam[i] > 0) || (X[i] >= u[i] - eps && lam[i] < 0);
    // direction: Newton on the free unknowns, scaled gradient on the ε-active ones
    s.set_active(active);
    Eigen::VectorXd top(n);
    for (int i = 0; i < n; ++i) top[i] = active[i] ? -lam[i] / D[i] : -lam[i];
    Eigen::VectorXd zero;
    if (s.saddle) zero = Eigen::VectorXd::Zero(s.blocks.C.rows());
    s.y_last.setZero();  // a direction: CG from 0
    const Eigen::VectorXd p = s.solve_tilde(top, s.saddle ? &zero : nullptr, cg_tolerance(X, true));
    // Armijo along the projection arc X(t) = P(X + t p)
    double t = 1.0;
    bool accepted = false;
    Eigen::VectorXd Xt(n);
    while (t > 1e-20) {
      for (int i = 0; i < n; ++i) Xt[i] = std::clamp(X[i] + t * p[i], l[i], u[i]);
      const Eigen::VectorXd step = Xt - X;
      const double decrease = -(lam.dot(step) + 0.5 * step.dot(s.form.apply(step)));  // f(X) − f(X(t))
      double predicted = 0.0;
      for (int i = 0; i < n; ++i) predicted += active[i] ? lam[i] * (X[i] - Xt[i]) : -t * lam[i] * p[i];
      if (decrease >= sigma * predicted) {
        accepted = true;
        break;
      }
      t *= 0.5;
    }
    if (!accepted) {
      result.X = X;
      return finish("projected Newton line search stalled");
    }
    X = Xt;
  }
  result.X = X;
  return finish("projected Newton after a cycling active set");
}

}  // namespace cdyn
