// friction_ssn.cpp — the semismooth Newton (active set) method for the frictional step
// problem, around a bound-QP step solver (qp/friction_solvers.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/qp/friction_solvers.hpp"
#include "cdyn/qp/kkt.hpp"

namespace cdyn {

namespace {

// The tangential set of one contact: sticking, or slipping along sigma (|sigma| = 1).
struct Tangential {
  bool stick = true;
  std::vector<double> sigma;
};

// The sets of (X, λ) for thresholds s (qp/friction_qp.hpp, slip_sets).
std::vector<Tangential> sets_of(const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                                const Eigen::VectorXd& s, const Eigen::VectorXd& D) {
  std::vector<char> stick;
  Eigen::VectorXd direction;
  slip_sets(f, X, reaction, s, D, stick, direction);
  std::vector<Tangential> sets(f.contacts.size());
  for (std::size_t k = 0; k < sets.size(); ++k) {
    sets[k].stick = stick[k] != 0;
    if (!sets[k].stick)
      for (int t : f.contacts[k].tangential) sets[k].sigma.push_back(direction[t]);
  }
  return sets;
}

// The same sticking nodes, and slip directions equal to 1e-12 (in the plane σ = ±1:
// exactly equal or not at all; in space σ is a unit vector of the tangent plane, which
// the iteration below converges to as a fixed point, not in finitely many steps).
bool same_sets(const std::vector<Tangential>& a, const std::vector<Tangential>& b) {
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (a[k].stick != b[k].stick || a[k].sigma.size() != b[k].sigma.size()) return false;
    for (std::size_t j = 0; j < a[k].sigma.size(); ++j)
      if (std::abs(a[k].sigma[j] - b[k].sigma[j]) > 1e-12) return false;
  }
  return true;
}

// The bound QP of the sets: stick → lower = upper = X̂_T; slip → free, r_T − s σ.
void apply_sets(BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& r0, const std::vector<Tangential>& sets,
                const Eigen::VectorXd& s) {
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const FrictionContact& c = f.contacts[k];
    for (std::size_t j = 0; j < c.tangential.size(); ++j) {
      const int t = c.tangential[j];
      if (sets[k].stick) {
        qp.lower[t] = qp.upper[t] = f.reference[t];
        qp.r[t] = r0[t];
      } else {
        qp.lower[t] = -inf;
        qp.upper[t] = inf;
        qp.r[t] = r0[t] - s[k] * sets[k].sigma[j];
      }
    }
  }
}

}  // namespace

FrictionResult solve_friction_ssn(BoundQP& qp, const FrictionConditions& f, StepSolver& inner,
                                  const FrictionOptions& options, const FrictionResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  check_friction_qp(qp, f);
  const int max_iterations = options.max_iterations > 0 ? options.max_iterations : 50;
  const Eigen::VectorXd r0 = qp.r, lower0 = qp.lower, upper0 = qp.upper;
  const Eigen::VectorXd D = scaling_diagonal(qp);
  const int m = static_cast<int>(f.contacts.size());
  const bool space = in_space(f);

  // Start: the previous step's sets and thresholds; cold, every node sticking (the
  // bonded step, whose λ_N gives Coulomb's first thresholds).
  std::vector<Tangential> sets(m);
  Eigen::VectorXd s(m);
  const QPResult* inner_warm = nullptr;
  const bool warm = warm_start && warm_start->qp.X.size() == qp.size() &&
                    static_cast<int>(warm_start->stick.size()) == m;
  for (int k = 0; k < m; ++k) {
    const FrictionContact& c = f.contacts[k];
    s[k] = !c.coulomb ? c.threshold : warm ? warm_start->threshold[k] : 0.0;
    if (warm && !warm_start->stick[k]) {
      sets[k].stick = false;
      for (int t : c.tangential) sets[k].sigma.push_back(warm_start->direction[t]);
    }
  }
  if (warm) inner_warm = &warm_start->qp;

  FrictionResult result;
  QPResult last;
  int inner_iterations = 0, fallbacks = 0;
  std::vector<std::vector<Tangential>> visited;  // the sets tried for the current s
  double last_tresca = std::numeric_limits<double>::infinity();  // the last Tresca residual for s
  std::string detail;
  int it = 0;
  for (;;) {
    ++it;
    apply_sets(qp, f, r0, sets, s);
    last = inner.solve(qp, inner_warm);
    inner_warm = &last;
    inner_iterations += last.iterations;
    // λ = S X − r0: the inner reaction is S X − r, r = r0 − s σ on the slipping unknowns
    Eigen::VectorXd reaction = last.reaction + (qp.r - r0);
    const Eigen::VectorXd s_new = friction_thresholds(f, reaction);
    result.qp = last;
    result.qp.reaction = std::move(reaction);
    result.threshold = s_new;
    qp.r = r0;  // (the residual's scale is that of (FQP); apply_sets rewrites r)
    qp.lower = lower0;
    qp.upper = upper0;
    result.residual = friction_residual(qp, f, last.X, result.qp.reaction, s_new, D);
    result.converged = result.residual <= options.tol;
    if (result.converged) break;
    if (it >= max_iterations) {
      detail = "maximum number of outer iterations reached";
      break;
    }
    // Newton's step for the Tresca problem of the current thresholds s ...
    std::vector<Tangential> next = sets_of(f, last.X, result.qp.reaction, s, D);
    visited.push_back(sets);
    // (in space the slip directions are not finitely many, and the iteration on them
    // converges only linearly — measured, a factor 0.3 an iteration on the plate of
    // test_friction_3d.cpp, each round of Coulomb's thresholds restarting it: a Tresca
    // residual that does not fall tenfold in an iteration is this method's cycling there)
    const double tresca_residual = friction_residual(qp, f, last.X, result.qp.reaction, s, D);
    const bool stalled = space && tresca_residual > 0.1 * last_tresca;
    last_tresca = tresca_residual;
    const bool cold_start = it == 1 && !warm;
    // (the Tresca problem of s is solved when the sets repeat — in the plane — or its
    // residual is below tol: in space σ = y/|y| repeats only to the accuracy of y)
    if (same_sets(next, sets) || tresca_residual <= options.tol || cold_start) {
      // ... solved (or the bonded start): Coulomb's fixed point takes s = μ λ_N (for
      // Tresca nothing is left to do: the residual is the inner solver's)
      if (!cold_start && (s_new - s).lpNorm<Eigen::Infinity>() == 0.0) {
        detail = "the sets and thresholds repeat above tol: the inner solver's tol is too loose";
        break;
      }
      s = s_new;
      next = sets_of(f, last.X, result.qp.reaction, s, D);
      visited.clear();
      last_tresca = std::numeric_limits<double>::infinity();
    } else if (stalled ||
               std::any_of(visited.begin(), visited.end(), [&](const auto& v) { return same_sets(v, next); })) {
      // ... cycling (Newton's method for a nonsmooth equation converges only locally):
      // the Tresca problem of s by projected Gauss–Seidel, globally convergent, whose
      // solution gives the sets of the next Newton step.
      if (qp.saddle) {
        detail = "the active sets cycle, and the saddle form has no projected Gauss-Seidel fallback";
        break;
      }
      // In space, where the outer fixed point on Coulomb's thresholds would restart this
      // for every new s (measured: a contraction of about 0.2 per round, each round
      // stalling first), the whole problem goes to projected Gauss–Seidel, thresholds
      // included; its solution gives both the sets and s.
      FrictionConditions tresca = f;
      if (!space)
        for (int k = 0; k < m; ++k) {
          tresca.contacts[k].coulomb = false;
          tresca.contacts[k].threshold = s[k];
        }
      FrictionOptions pgs = options;
      pgs.throw_on_failure = false;
      const FrictionResult g = solve_friction_pgs(qp, tresca, pgs, &result);
      ++fallbacks;
      inner_iterations += g.qp.iterations;
      if (space) s = g.threshold;
      next = sets_of(f, g.qp.X, g.qp.reaction, s, D);
      visited.clear();
      last_tresca = std::numeric_limits<double>::infinity();
    }
    sets = next;
  }
  qp.r = r0;
  qp.lower = lower0;
  qp.upper = upper0;
  slip_sets(f, result.qp.X, result.qp.reaction, result.threshold, D, result.stick, result.direction);
  result.status = contact_status(qp, f, result.qp.X, result.qp.reaction);
  result.qp.iterations = inner_iterations;
  result.fallbacks = fallbacks;
  result.qp.kkt_residual = result.residual;
  result.qp.converged = result.converged;
  result.qp.active = active_set(qp, result.qp.X, result.qp.reaction, D);
  result.qp.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result.converged && options.throw_on_failure)
    throw NumericalError("friction (semismooth Newton around " + inner.name() + "): did not converge: residual " +
                         to_text(result.residual) + " > tol " + to_text(options.tol) + " after " +
                         std::to_string(it) + " outer iterations, " + std::to_string(fallbacks) +
                         " projected Gauss-Seidel fallbacks (" + detail + ")");
  return result;
}

}  // namespace cdyn
