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

// The tangential set of one contact: sticking, or slipping along sigma (|sigma| = 1),
// in space with the direction's Newton coefficient kappa (below; 0: σ held).
struct Tangential {
  bool stick = true;
  std::vector<double> sigma;
  double kappa = 0.0;
};

// The largest κ over the contact's D_k (κ = s/|d| grows without bound as a slipping
// contact comes to rest; any κ ≥ 0 leaves the solution as it is, only the iteration's
// speed depends on it, and CG's conditioning on κ/D_k).
constexpr double kLargestKappa = 1e3;

// The sets of (X, λ) for thresholds s (qp/friction_qp.hpp, slip_sets).
//
// In space a slipping contact's force is λ_T = −s d/|d| (d = X_T − X̂_T), and holding
// its direction σ fixed — the plane's rule, where σ = ±1 — makes the iteration on σ a
// fixed point that converges slowly or not at all (measured on the sliding plate of
// data/scenes/incline_block_3d.toml: residual 0.12 after 50 iterations).  Newton's
// linearization of d ↦ s d/|d| at the rule's predicted slip d̃ ∥ σ is
//     λ_T ≈ −s σ − κ (I − σσᵀ) d,    κ = s/|d̃|,
// a symmetric positive semidefinite term on the contact's tangential block; it vanishes
// where d ∥ σ, so it changes the iterates and not the solution.  Taken with `newton`:
// on subdomains, where the projected Gauss–Seidel fallback below does not run.  On one
// process the fallback is cheaper (the plate: 0.87 ms a step against 12.4 ms with the
// Newton terms, S changing at every iteration and factorized again each time).
std::vector<Tangential> sets_of(const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                                const Eigen::VectorXd& s, const Eigen::VectorXd& D, bool newton) {
  std::vector<char> stick;
  Eigen::VectorXd direction;
  std::vector<double> slip_length;
  slip_sets(f, X, reaction, s, D, stick, direction, &slip_length);
  std::vector<Tangential> sets(f.contacts.size());
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::vector<int>& t = f.contacts[k].tangential;
    sets[k].stick = stick[k] != 0;
    if (sets[k].stick) continue;
    for (int j : t) sets[k].sigma.push_back(direction[j]);
    if (!newton || t.size() < 2) continue;
    double Dk = std::numeric_limits<double>::infinity();
    for (int j : t) Dk = std::min(Dk, D[j]);
    sets[k].kappa = std::min(s[k] / slip_length[k], kLargestKappa * Dk);
  }
  return sets;
}

// The Newton term of the slipping contacts in space (sets_of) added to S's tangential
// blocks and to r (κ (I − σσᵀ) X̂_T) where this rank owns the unknowns, S's entries
// restored by undo() (or when it goes out of scope).  S changed in place is renamed
// (BoundQP::matrices_id) while the terms are in, and takes its name back with its
// entries: the inner solver must not take it for the S it saw last.
class DirectionTerms {
 public:
  DirectionTerms(BoundQP& qp, const FrictionConditions& f, const std::vector<Tangential>& sets, const StepSolver& inner)
      : qp_(qp), id_(qp.matrices_id) {
    std::vector<std::size_t> taken;
    for (std::size_t k = 0; k < sets.size(); ++k)
      if (sets[k].kappa > 0.0 && inner.owns(f.contacts[k].tangential[0])) taken.push_back(k);
    // (a vertex's block is in S's pattern; were an entry not, coeffRef would insert it
    // and move the others: every entry is made first, then the pointers taken)
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t k : taken) {
        const std::vector<int>& t = f.contacts[k].tangential;
        const std::vector<double>& sigma = sets[k].sigma;
        for (std::size_t i = 0; i < t.size(); ++i)
          for (std::size_t j = 0; j < t.size(); ++j) {
            double& entry = qp.S.coeffRef(t[i], t[j]);
            if (pass == 0) continue;
            const double P = (i == j ? 1.0 : 0.0) - sigma[i] * sigma[j];
            saved_.emplace_back(&entry, entry);
            entry += sets[k].kappa * P;
            qp.r[t[i]] += sets[k].kappa * P * f.reference[t[j]];
          }
      }
    if (!saved_.empty()) qp.matrices_id = new_matrices_id();
  }
  ~DirectionTerms() { undo(); }
  DirectionTerms(const DirectionTerms&) = delete;
  DirectionTerms& operator=(const DirectionTerms&) = delete;
  void undo() {
    if (saved_.empty()) return;
    for (const auto& [entry, value] : saved_) *entry = value;
    saved_.clear();
    qp_.matrices_id = id_;
  }

 private:
  BoundQP& qp_;
  const std::uint64_t id_;  // S's name without the terms
  std::vector<std::pair<double*, double>> saved_;
};

// The friction forces of the sets at X: s σ, and in space + κ (I − σσᵀ) d (sets_of), on
// every unknown of the QP (zero off the slipping contacts).
Eigen::VectorXd friction_forces(const FrictionConditions& f, const std::vector<Tangential>& sets,
                                const Eigen::VectorXd& s, const Eigen::VectorXd& X) {
  Eigen::VectorXd force = Eigen::VectorXd::Zero(X.size());
  for (std::size_t k = 0; k < sets.size(); ++k) {
    if (sets[k].stick) continue;
    const std::vector<int>& t = f.contacts[k].tangential;
    const std::vector<double>& sigma = sets[k].sigma;
    double along = 0.0;  // σ·d
    for (std::size_t i = 0; i < t.size(); ++i) along += sigma[i] * (X[t[i]] - f.reference[t[i]]);
    for (std::size_t i = 0; i < t.size(); ++i) {
      force[t[i]] = s[k] * sigma[i];
      if (sets[k].kappa > 0.0) force[t[i]] += sets[k].kappa * (X[t[i]] - f.reference[t[i]] - along * sigma[i]);
    }
  }
  return force;
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

// The same sets on every rank holding a share of the QP (on one process, same_sets).
bool same_sets(const std::vector<Tangential>& a, const std::vector<Tangential>& b, const StepSolver& inner) {
  return inner.largest(same_sets(a, b) ? 0.0 : 1.0) == 0.0;
}

// The bound QP of the sets: stick → lower = upper = X̂_T; slip → free, r_T − s σ,
// where this rank owns the unknown (StepSolver::owns: the ranks' summed r has each
// force once).
void apply_sets(BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& r0,
                const std::vector<Tangential>& sets, const Eigen::VectorXd& s, const StepSolver& inner) {
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
        qp.r[t] = inner.owns(t) ? r0[t] - s[k] * sets[k].sigma[j] : r0[t];
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
  // On a share of the QP (StepSolver::solves_a_share) the tests below measure the whole
  // problem: its r and diagonal summed over the ranks, the residuals' maxima and the
  // sets' agreement taken over them, so that every rank takes the same branch.
  const bool share = inner.solves_a_share();
  const Eigen::VectorXd D = inner.summed(scaling_diagonal(qp));
  const Eigen::VectorXd r_whole = share ? inner.summed(r0) : r0;
  const int m = static_cast<int>(f.contacts.size());
  const bool space = inner.largest(in_space(f) ? 1.0 : 0.0) > 0.0;
  // (FQP)'s residual, the whole problem's: with the summed r (its scale)
  auto residual = [&](const Eigen::VectorXd& X, const Eigen::VectorXd& reaction, const Eigen::VectorXd& thresholds) {
    qp.r = r_whole;
    const double F = friction_residual(qp, f, X, reaction, thresholds, D);
    qp.r = r0;
    return inner.largest(F);
  };

  // Start: the previous step's sets and thresholds; cold, every node sticking (the
  // bonded step, whose λ_N gives Coulomb's first thresholds).
  std::vector<Tangential> sets(m);
  Eigen::VectorXd s(m);
  const QPResult* inner_warm = nullptr;
  const bool warm = inner.largest(warm_start && warm_start->qp.X.size() == qp.size() &&
                                          static_cast<int>(warm_start->stick.size()) == m
                                      ? 0.0
                                      : 1.0) == 0.0;  // (on every rank)
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
    apply_sets(qp, f, r0, sets, s, inner);
    DirectionTerms directions(qp, f, sets, inner);
    last = inner.solve(qp, inner_warm);
    directions.undo();
    inner_warm = &last;
    inner_iterations += last.iterations;
    // λ = S X − r0: the inner reaction is S X − r with r = r0 − s σ on the slipping
    // unknowns, and in space S and r with the directions' terms: λ = that − the forces
    // (the whole r's, each force counted once over the ranks; in the plane written as
    // r − r0, the difference the solver saw on one process)
    const Eigen::VectorXd force = friction_forces(f, sets, s, last.X);
    Eigen::VectorXd reaction = last.reaction + ((r0 - force) - r0);
    const Eigen::VectorXd s_new = friction_thresholds(f, reaction);
    result.qp = last;
    result.qp.reaction = std::move(reaction);
    result.threshold = s_new;
    qp.r = r0;  // (apply_sets rewrites r)
    qp.lower = lower0;
    qp.upper = upper0;
    result.residual = residual(last.X, result.qp.reaction, s_new);
    result.converged = result.residual <= options.tol;
    if (result.converged) break;
    if (it >= max_iterations) {
      detail = "maximum number of outer iterations reached";
      break;
    }
    // Newton's step for the Tresca problem of the current thresholds s ...
    std::vector<Tangential> next = sets_of(f, last.X, result.qp.reaction, s, D, share);
    visited.push_back(sets);
    // (in space the slip directions are not finitely many, and the iteration on them
    // converges only linearly — measured, a factor 0.3 an iteration on the plate of
    // test_friction_3d.cpp, each round of Coulomb's thresholds restarting it: a Tresca
    // residual that does not fall tenfold in an iteration is this method's cycling there;
    // not on subdomains, whose directions' Newton terms have no fallback to go to)
    const double tresca_residual = residual(last.X, result.qp.reaction, s);
    const bool stalled = space && !share && tresca_residual > 0.1 * last_tresca;
    last_tresca = tresca_residual;
    const bool cold_start = it == 1 && !warm;
    // (the Tresca problem of s is solved when the sets repeat — in the plane — or its
    // residual is below tol: in space σ = y/|y| repeats only to the accuracy of y)
    if (same_sets(next, sets, inner) || tresca_residual <= options.tol || cold_start) {
      // ... solved (or the bonded start): Coulomb's fixed point takes s = μ λ_N (for
      // Tresca nothing is left to do: the residual is the inner solver's)
      if (!cold_start && inner.largest((s_new - s).lpNorm<Eigen::Infinity>()) == 0.0) {
        detail = "the sets and thresholds repeat above tol: the inner solver's tol is too loose";
        break;
      }
      s = s_new;
      next = sets_of(f, last.X, result.qp.reaction, s, D, share);
      visited.clear();
      last_tresca = std::numeric_limits<double>::infinity();
    } else if (stalled || std::any_of(visited.begin(), visited.end(),
                                      [&](const auto& v) { return same_sets(v, next, inner); })) {
      // ... cycling (Newton's method for a nonsmooth equation converges only locally):
      // the Tresca problem of s by projected Gauss–Seidel, globally convergent, whose
      // solution gives the sets of the next Newton step.
      if (qp.saddle || share) {
        detail = std::string("the active sets cycle, and ") +
                 (share ? "a run on subdomains" : "the saddle form") + " has no projected Gauss-Seidel fallback";
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
      next = sets_of(f, g.qp.X, g.qp.reaction, s, D, share);
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
