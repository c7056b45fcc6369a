// pdas.cpp — the primal-dual active set iteration (Hintermüller–Ito–Kunisch 2002) on the
// step QP; the linear algebra is behind ReducedSystem, the fallback after a cycle in
// projected_newton.cpp.  See pdas.hpp.
#include "cdyn/qp/pdas/pdas.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/qp/pdas/explicit_reduced_system.hpp"
#include "cdyn/qp/pdas/projected_newton.hpp"
#include "cdyn/qp/pdas/saddle_reduced_system.hpp"

namespace cdyn {

namespace {

// The state of every unknown: free, or held at its lower or upper bound.
constexpr signed char kFree = 0, kLower = -1, kUpper = 1;
using ActiveSet = std::vector<signed char>;

// The first active set: the fixed unknowns (lower = upper); with a warm start, also the
// previous result's active unknowns, each held at its nearer bound.  (A cold start thus
// begins with the unconstrained solution.)
ActiveSet initial_active_set(const BoundQP& qp, const QPResult* warm_start) {
  const int n = qp.size();
  const Eigen::VectorXd& l = qp.lower;
  const Eigen::VectorXd& u = qp.upper;
  ActiveSet state(n, kFree);
#pragma omp parallel for schedule(static) if (2L * n >= kParallelWork)
  for (int i = 0; i < n; ++i)
    if (l[i] == u[i]) state[i] = kLower;
  if (!warm_start || warm_start->X.size() != n) return state;
  for (int i : warm_start->active) {
    if (i < 0 || i >= n || state[i] != kFree) continue;
    const double xi = warm_start->X[i];
    const bool has_l = std::isfinite(l[i]), has_u = std::isfinite(u[i]);
    if (has_l && (!has_u || std::abs(xi - l[i]) <= std::abs(xi - u[i])))
      state[i] = kLower;
    else if (has_u)
      state[i] = kUpper;
  }
  return state;
}

// The PDAS rule (HIK 2002, with the scaling D for their constant c): the next active
// set from (X, λ), A_l = {λ_i + D_i(lower_i − X_i) > 0}, A_u = {λ_i + D_i(upper_i − X_i) < 0}
// — the rule of QPResult::active (kkt.hpp's active_set), written as a difference.  In
// the same pass, what the iteration asks of the new set: how many unknowns change
// state, and the KKT measure's maxima ‖F‖∞ and ‖X‖∞ (kkt.hpp; the scale's ‖D⁻¹r‖∞ is
// fixed in a solve) — one pass over the vectors instead of three (the rule, the set's
// comparison, kkt_residual), each entry computed as kkt_maxima computes it.
struct NextSet {
  ActiveSet state;
  long changes = 0;
  double F = 0.0, x_max = 0.0;
  bool finite = true;
  double kkt_residual(double r_scale) const {
    return KKTMaxima{finite ? F : std::numeric_limits<double>::infinity(), std::max(x_max, r_scale)}.residual();
  }
};
NextSet pdas_rule(const BoundQP& qp, const Eigen::VectorXd& D, const Eigen::VectorXd& X, const Eigen::VectorXd& lam,
                  const ActiveSet& state) {
  const Eigen::VectorXd& l = qp.lower;
  const Eigen::VectorXd& u = qp.upper;
  const int n = qp.size();
  NextSet next;
  next.state.assign(n, kFree);
  ActiveSet& st = next.state;
  long changes = 0;
  double F = 0.0, x_max = 0.0;
  bool finite = true;
#pragma omp parallel for schedule(static) reduction(+ : changes) reduction(max : F, x_max) reduction(&& : finite) \
    if (6L * n >= kParallelWork)
  for (int i = 0; i < n; ++i) {
    if (l[i] == u[i])
      st[i] = kLower;
    else if (std::isfinite(l[i]) && lam[i] + D[i] * (l[i] - X[i]) > 0)
      st[i] = kLower;
    else if (std::isfinite(u[i]) && lam[i] + D[i] * (u[i] - X[i]) < 0)
      st[i] = kUpper;
    changes += st[i] != state[i];
    const double f = std::abs(natural_residual_entry(qp, X, lam, D, i));
    finite = finite && std::isfinite(f);
    F = std::max(F, f);
    x_max = std::max(x_max, std::abs(X[i]));
  }
  next.changes = changes;
  next.F = F;
  next.x_max = x_max;
  next.finite = finite;
  return next;
}

// The held unknowns of an active set and the bound values they are held at (0 elsewhere);
// returns ‖value‖∞ (for SolveTolerance).
double held_at_bounds(const BoundQP& qp, const ActiveSet& state, HeldSet& held, Eigen::VectorXd& value) {
  const int n = qp.size();
  held.resize(n);
  value.resize(n);
  double value_max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : value_max) if (2L * n >= kParallelWork)
  for (int i = 0; i < n; ++i) {
    held[i] = state[i] != kFree;
    value[i] = state[i] == kFree ? 0.0 : state[i] == kLower ? qp.lower[i] : qp.upper[i];
    value_max = std::max(value_max, std::abs(value[i]));
  }
  return value_max;
}

// The unknowns an active set holds, in increasing order: QPResult::active when λ is the
// one the set was made from (the rule above is active_set's).
std::vector<int> held_list(const ActiveSet& state) {
  return indices_where(static_cast<int>(state.size()), [&](int i) { return state[i] != kFree; });
}

// At most two steps of iterative refinement of a result above tol, with the same
// factorization: X += y, S̃ y = −λ on the free rows (0 on the held ones).
void refine(const BoundQP& qp, const QuadraticForm& form, ReducedSystem& system, const HeldSet& held,
            double solve_tol, double tol, QPResult& result) {
  for (int k = 0; k < 2 && !result.converged; ++k) {
    Eigen::VectorXd b = -result.reaction;
    for (std::size_t i = 0; i < held.size(); ++i)
      if (held[i]) b[i] = 0.0;
    result.X += system.solve_correction(b, solve_tol);
    finish_result(qp, form, tol, result);
  }
}

}  // namespace

struct PDASSolver::Impl {
  QPOptions opt;
  Counters counters;
  CheckedMatrices checked;
  QuadraticForm form;
  ExplicitReducedSystem explicit_system{opt, counters};
  SaddleReducedSystem saddle_system{counters};
  ReducedSystem* system = nullptr;  // the one of the last problem
  bool diagonal_checked = false;    // D > 0 was checked for the current matrices
};

PDASSolver::PDASSolver(const QPOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->opt = options;
  if (impl_->opt.max_iterations == 0) impl_->opt.max_iterations = 100;
}
PDASSolver::~PDASSolver() = default;

void PDASSolver::clear() {
  const QPOptions options = impl_->opt;
  impl_ = std::make_unique<Impl>();
  impl_->opt = options;
}
void PDASSolver::next_in_same_step(bool to_round_off) {
  // (the saddle form keeps no such count, and solves by its LU)
  impl_->explicit_system.next_in_same_step(to_round_off);
}
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
    if (s.system && result.X.size() == n) s.system->set_first_guess(result.X);  // CG's next start
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_failure("pdas", opt, result, detail);
    return result;
  };
  if (n == 0) {
    s.form.set(qp);
    result.X.resize(0);
    return finish("");
  }
  s.form.set(qp, !new_matrices);
  if (qp.saddle && opt.pdas_cg_only)
    throw InputError("linear", "the CG path needs an explicit step matrix; this pair's step is in saddle form "
                               "(H^h continuous: P1+/P1, P2/P1), solved by UMFPACK");
  s.system = qp.saddle ? static_cast<ReducedSystem*>(&s.saddle_system) : &s.explicit_system;
  ReducedSystem& system = *s.system;
  system.prepare(qp, new_matrices);
  const Eigen::VectorXd& D = s.form.diagonal();
  if (new_matrices) s.diagonal_checked = false;
  if (!s.diagonal_checked) {  // (once per S: D is the last call's otherwise)
    for (int i = 0; i < n; ++i)
      if (!(D[i] > 0)) throw NumericalError("pdas: S has a non-positive diagonal entry: it is not positive definite");
    s.diagonal_checked = true;
  }

  ActiveSet state = initial_active_set(qp, warm_start);
  if (warm_start && warm_start->X.size() == n) system.set_first_guess(warm_start->X);
  const SolveTolerance tolerance(qp, D, opt.tol);
  std::set<ActiveSet> seen;
  HeldSet held, held0;           // this iterate's held set and the last one's
  Eigen::VectorXd value, X, X0, lam;  // X0: the last iterate, whose λ lam holds
  bool tight = false;            // this iterate confirms a repeat found on a loose solve
  bool refactorized = false;     // the one fresh factorization has been spent
  bool cycled = false;
  double held_max = 0.0;
  int it = 0;
  while (it < opt.max_iterations) {
    ++it;
    result.iterations = it;
    NextSet next;
    if (!tight) {
      // Newton step: the minimizer with the active set held at its bounds.
      X0.swap(X);
      held0.swap(held);
      held_max = held_at_bounds(qp, state, held, value);
      X = system.solve_fixed(qp, held, value, tolerance(held_max, false));
      const ReducedSystem::Iterate last{X0, held0};
      system.reaction(qp, s.form, X, held, lam, it > 1 ? &last : nullptr);
      next = pdas_rule(qp, D, X, lam, state);
      if (next.changes == 0 && system.last_residual() > tolerance(held_max, true)) {
        tight = true;  // a repeat on a loose solve: confirm it on the same system solved to tol/2
        system.resume_next();
        continue;
      }
    } else {
      // The confirmation: the same held set and values, the interrupted solve resumed;
      // λ from a whole product at once, since a repeat ends the iteration with it (an
      // inexact solve's updated residual has drifted by round-off) — the rule on the
      // product's λ is the final test's active set, and its maxima the final residual.
      X = system.solve_fixed(qp, held, value, tolerance(held_max, true));
      lam = s.form.gradient(X);
      next = pdas_rule(qp, D, X, lam, state);
    }
    const bool lam_exact = tight || !system.last_inexact();
    tight = false;
    if (next.changes == 0) {
      // X is exact up to the linear solve.  λ from a whole product (an inexact solve's
      // updated residual has drifted by round-off); refine if the residual says so.
      result.X = X;
      if (!lam_exact) {
        lam = s.form.gradient(X);
        result.kkt_residual = kkt_residual(qp, X, lam, &D);
        result.active = active_set(qp, X, lam, D);
      } else {
        result.kkt_residual = next.kkt_residual(tolerance.r_scale());
        result.active = held_list(state);
      }
      result.reaction = lam;
      result.converged = result.kkt_residual <= opt.tol;
      refine(qp, s.form, system, held, tolerance(held_max, true), opt.tol, result);
      if (!result.converged && !refactorized && system.refactorization_may_help()) {
        refactorized = true;  // row updates or CG may have lost accuracy: a fresh factor, solve again
        system.set_held(held, /*fresh=*/true);
        continue;
      }
      finished = true;
      return finish("active set repeated but the residual stays above tol: S is ill-conditioned");
    }
    if (next.kkt_residual(tolerance.r_scale()) <= opt.tol) {
      // Degenerate unknowns (λ_i ≈ 0 at the bound) may still switch: X is good if the
      // residual with the whole product says so too (finish_result recomputes λ that way).
      result.X = X;
      finish_result(qp, s.form, opt.tol, result);
      finished = result.converged;
      if (finished) return finish("");
    }
    if (seen.count(next.state)) {
      // An active set comes back: PDAS would go round for ever.  Monotone convergence
      // holds only for an M-matrix S (HIK 2002, Thm 3.3) and exact solves.
      cycled = true;
      break;
    }
    seen.insert(state);
    state = std::move(next.state);
  }
  if (!cycled) {
    result.X = X;
    return finish("no convergence of the active set");
  }
  const ProjectedNewtonResult pn = projected_newton(qp, s.form, system, X, it, opt, tolerance, s.counters);
  result.X = pn.X;
  result.iterations = pn.iterations;
  return finish(pn.failure);
}

}  // namespace cdyn
