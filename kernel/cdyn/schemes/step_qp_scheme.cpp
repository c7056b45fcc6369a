// step_qp_scheme.cpp — the step QP S = aA + kM, built once and solved with warm starts.
#include "cdyn/schemes/step_qp_scheme.hpp"

#include <algorithm>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/qp/friction_solvers.hpp"
#include "cdyn/qp/kkt.hpp"
#ifdef CDYN_WITH_IPOPT
#include "cdyn/qp/friction_ipopt.hpp"
#endif

namespace cdyn {

StepQPScheme::StepQPScheme(const ConstrainedProblem& p, StepSolver& solver, double dt, double a, double m,
                           bool condense, const RayleighDamping& damping, double s, double friction_tol)
    : p_(p), solver_(solver), dt_(dt), damping_(damping), condense_(condense), M_(sparse_mass(*p.mass)),
      slip_factor_(s), friction_tol_(friction_tol) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw InputError("dt", "must be positive and finite (got " + to_text(dt) + ")");
  // (H^h = W^h, P1/P1: M = C is sparse after all, sparse_mass: an explicit S, one
  // Cholesky factor, instead of the saddle form, an LU of a matrix twice the size per
  // active set)
  build(a + s * damping.beta / dt, m + s * damping.alpha * dt);  // + (s/dt)(αM + βA)
  // (on a share of the QP a rank whose cells touch no rough obstacle has no friction
  // node, but solves (FQP) with the others)
  with_friction_ = solver_.largest(p_.friction.empty() ? 0.0 : 1.0) > 0.0;
}

void StepQPScheme::build(double a, double m) {
  a_ = a;
  m_ = m;
  const double k = m / (dt_ * dt_);
  qp_.lower = p_.lower;
  qp_.upper = p_.upper;
  qp_.saddle.reset();
  condensation_.reset();
  D_.resize(0);
  has_last_ = false;
  has_friction_last_ = false;
  if (!M_) {
    qp_.S = SparseMatrix();
    qp_.saddle = p_.mass->saddle(SparseMatrix(a_ * p_.A), k);
    qp_.matrices_id = new_matrices_id();
    map_friction();
    tell_unknowns();
    return;
  }
  qp_.S = a_ * p_.A + k * *M_;
  qp_.S.makeCompressed();
  if (condense_) {
    // The friction term |X_T − X̂_T| is not quadratic: the tangential unknowns are kept
    // (marked bounded for the condensation; the step's bounds are p_'s).
    Eigen::VectorXd keep = p_.lower;
    for (const FrictionNode& node : p_.friction)
      for (int t : node.tangential) keep[t] = 0.0;
    StaticCondensation c(qp_.S, keep, p_.upper, bubble_unknowns(p_), !solver_.solves_a_share());
    if (c.n_condensed() > 0) {
      qp_.S = c.S_c();  // (c keeps the full S, for set_bounds)
      qp_.lower = c.kept(p_.lower);
      qp_.upper = c.kept(p_.upper);
      condensation_.emplace(std::move(c));
    }
  }
  qp_.matrices_id = new_matrices_id();
  map_friction();
  tell_unknowns();
}

void StepQPScheme::tell_unknowns() {
  if (condensation_) {
    solver_.set_unknowns(condensation_->kept_unknowns());
    return;
  }
  std::vector<int> free_unknowns(p_.n_free());
  for (int i = 0; i < p_.n_free(); ++i) free_unknowns[i] = i;
  solver_.set_unknowns(free_unknowns);
}

void StepQPScheme::map_friction() {
  friction_.contacts.clear();
  if (p_.friction.empty()) return;
  // index of each unknown in the step QP (−1: condensed)
  std::vector<int> index(p_.n_free());
  for (int i = 0; i < p_.n_free(); ++i) index[i] = i;
  if (condensation_) {
    const std::vector<int>& kept = condensation_->kept_unknowns();
    std::fill(index.begin(), index.end(), -1);
    for (std::size_t j = 0; j < kept.size(); ++j) index[kept[j]] = static_cast<int>(j);
  }
  for (const FrictionNode& node : p_.friction) {
    FrictionContact c;
    c.normal = index[node.normal];
    for (int t : node.tangential) c.tangential.push_back(index[t]);
    c.coulomb = node.law == FrictionLaw::Coulomb;
    c.mu = node.mu;
    c.threshold = node.threshold;
    // (a vertex unknown is coupled to its neighbours: never condensed)
    if (c.normal < 0 || *std::min_element(c.tangential.begin(), c.tangential.end()) < 0)
      throw NumericalError("friction: a contact unknown was condensed");
    friction_.contacts.push_back(std::move(c));
  }
  has_friction_last_ = false;
}

Eigen::VectorXd StepQPScheme::owned_part(const Eigen::VectorXd& x) const {
  if (!solver_.solves_a_share()) return x;
  Eigen::VectorXd out = x;
  for (int j = 0; j < static_cast<int>(qp_.lower.size()); ++j)  // (the QP's unknowns)
    if (!solver_.owns(j)) out[condensation_ ? condensation_->kept_unknowns()[j] : j] = 0.0;
  return out;
}

void StepQPScheme::set_factors(double a, double m) {
  if (a == a_ && m == m_) return;
  build(a, m);
}

double StepQPScheme::damping_work(const Eigen::VectorXd& dU, double h) const {
  double w = 0.0;
  if (damping_.alpha > 0.0) w += damping_.alpha * dot(dU, mass_times(dU));
  if (damping_.beta > 0.0) w += damping_.beta * dot(dU, symmetric_times(p_.A, dU));
  return w / h;
}

Energy StepQPScheme::energy(const State& s) const {
  return {p_.mass->kinetic_energy(s.V), p_.potential_energy(s.U, s.t)};
}

Eigen::VectorXd StepQPScheme::mass_times(const Eigen::VectorXd& x) const {
  return p_.mass->momentum(p_.mass->velocity(x));
}

Eigen::VectorXd StepQPScheme::inertia(double a, const Eigen::VectorXd& U, double b, const Eigen::VectorXd& V) const {
  return p_.mass->momentum(a * p_.mass->velocity(U) + b * V);
}

void StepQPScheme::set_bounds(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  if (condensation_) {
    bool bounded = false;
    for (int i = 0; i < condensation_->n() && !bounded; ++i)
      bounded = condensation_->condenses(i) && (std::isfinite(lower[i]) || std::isfinite(upper[i]));
    if (!bounded) {
      qp_.lower = condensation_->kept(lower);
      qp_.upper = condensation_->kept(upper);
      return;
    }
    // a condensed unknown is bounded now: back to the full QP (the warm start's indices
    // were those of the condensed one)
    end_condensation();
  }
  qp_.lower = lower;
  qp_.upper = upper;
}

void StepQPScheme::end_condensation() {
  qp_.S = condensation_->S();
  qp_.matrices_id = new_matrices_id();
  qp_.lower = p_.lower;
  qp_.upper = p_.upper;
  condensation_.reset();
  D_.resize(0);
  has_last_ = false;
  map_friction();
  tell_unknowns();
}

SchemeMemory StepQPScheme::memory() const {
  SchemeMemory m;
  m.numbers["condensed"] = condensation_ ? 1.0 : 0.0;
  store_warm_start(m, "step_qp", last_, has_last_);
  for (const auto& [name, v] : remembered_) m.store_if_any(name, *v);
  if (has_friction_last_) {
    m.vectors["friction_threshold"] = friction_last_.threshold;
    m.vectors["friction_direction"] = friction_last_.direction;
    Eigen::VectorXd stick(friction_last_.stick.size());
    for (std::size_t k = 0; k < friction_last_.stick.size(); ++k) stick[k] = friction_last_.stick[k];
    m.vectors["friction_stick"] = stick;
  }
  return m;
}

void StepQPScheme::restore(const SchemeMemory& m) {
  solver_.clear();
  // a condensation ended by a bound stays ended (set_bounds); the factors a_, m_ are
  // those of a whole step between steps, as build() made them
  if (m.number("condensed") == 0.0 && condensation_) end_condensation();
  has_last_ = load_warm_start(m, "step_qp", last_);
  for (const auto& [name, v] : remembered_) *v = m.vector_or_empty(name);
  has_friction_last_ = with_friction_ && has_last_ && m.vectors.count("friction_stick");
  if (has_friction_last_) {
    friction_last_ = FrictionResult{};
    friction_last_.qp = last_;
    friction_last_.threshold = m.vector("friction_threshold");
    friction_last_.direction = m.vector("friction_direction");
    const Eigen::VectorXd& stick = m.vector("friction_stick");
    for (int k = 0; k < stick.size(); ++k) friction_last_.stick.push_back(stick[k] != 0.0);
  }
}

void StepQPScheme::constrain_at(double t) {
  if (p_.bounds_are_constant()) return;
  Eigen::VectorXd lower, upper;
  p_.bounds(t, lower, upper);
  set_bounds(lower, upper);
}

void StepQPScheme::solve_with_friction(State& s, StepStats& stats) {
  friction_.reference = condensation_ ? condensation_->kept(s.U) : s.U;  // X̂ = Uⁿ
  FrictionOptions options;
  options.tol = friction_tol_;
  const FrictionResult* warm = has_friction_last_ ? &friction_last_ : nullptr;
  if (solver_.name() == "pgs")
    friction_last_ = solve_friction_pgs(qp_, friction_, options, warm);
#ifdef CDYN_WITH_IPOPT
  else if (solver_.name() == "ipopt" && !qp_.saddle)
    friction_last_ = solve_friction_ipopt(qp_, friction_, options, warm);
#endif
  else
    friction_last_ = solve_friction_ssn(qp_, friction_, solver_, options, warm);
  has_friction_last_ = true;
  const Eigen::VectorXd& X = friction_last_.qp.X;
  const int m = static_cast<int>(friction_.contacts.size());
  std::vector<char> counted(m);  // (on a share, the contacts this rank owns: the ranks' works are summed)
  for (int k = 0; k < m; ++k) counted[k] = solver_.owns(friction_.contacts[k].normal);
  stats.friction_work = slip_factor_ * friction_work(friction_, X, friction_last_.threshold, counted);
  s.contact_status.resize(m);
  s.slip = Eigen::VectorXd::Zero(p_.n_free());
  for (int k = 0; k < m; ++k) {  // (friction_.contacts[k] is p_.friction[k] in the QP's numbering)
    const FrictionContact& c = friction_.contacts[k];
    s.contact_status[k] = static_cast<int>(friction_last_.status[k]);
    for (std::size_t j = 0; j < c.tangential.size(); ++j)
      s.slip[p_.friction[k].tangential[j]] = slip_factor_ * (X[c.tangential[j]] - friction_.reference[c.tangential[j]]);
  }
}

Eigen::VectorXd StepQPScheme::solve(const Eigen::VectorXd& r, State& s, StepStats& stats) {
  qp_.r = condensation_ ? condensation_->reduce(r) : r;  // r_c = r_v − S_vb S_bb⁻¹ r_b
  if (!with_friction_) {
    last_ = solver_.solve(qp_, has_last_ ? &last_ : nullptr);
  } else {
    solve_with_friction(s, stats);
    last_ = friction_last_.qp;
  }
  has_last_ = true;
  return report_last(r, s, stats);
}

// The stats, s.reaction and X of last_, the step QP's result for r.
Eigen::VectorXd StepQPScheme::report_last(const Eigen::VectorXd& r, State& s, StepStats& stats) const {
  stats.qp_iterations = last_.iterations;
  stats.qp_seconds = last_.seconds;
  stats.active = solver_.count_in_whole(last_.active);
  stats.kkt_residual = last_.kkt_residual;
  stats.converged = last_.converged;
  if (!condensation_) {
    s.reaction = last_.reaction;
    return last_.X;
  }
  s.reaction = condensation_->expand_reaction(last_.reaction);  // λ_b = 0
  return condensation_->expand(last_.X, r);                     // X_b = S_bb⁻¹ (r_b − S_bv X_v)
}

std::optional<Eigen::VectorXd> StepQPScheme::on_line(const Point& a, const Point& b, double theta,
                                                    const Eigen::VectorXd& r, double tol, State& s,
                                                    StepStats& stats) {
  if (!friction_.contacts.empty() || a.X.size() != qp_.size() || b.X.size() != qp_.size()) return std::nullopt;
  auto along = [theta](const Eigen::VectorXd& p, const Eigen::VectorXd& q) {
    return Eigen::VectorXd(p + theta * (q - p));
  };
  Eigen::VectorXd X = along(a.X, b.X);
  const Eigen::VectorXd reaction = along(a.reaction, b.reaction);
  hold_at_bounds(qp_, b.active, X);
  qp_.r = condensation_ ? condensation_->reduce(r) : r;
  if (D_.size() != qp_.size()) D_ = scaling_diagonal(qp_);
  // On the points' active set the interpolate is exact (to round-off); off it, it is not
  // the solution, however small its residual: the set must be the same.
  std::vector<int> active = active_set(qp_, X, reaction, D_);
  const double residual = kkt_residual(qp_, X, reaction, &D_);
  if (active != b.active || !(residual <= tol)) return std::nullopt;
  last_.X = std::move(X);  // the warm start of the next solve, as a solve's result would be
  last_.reaction = reaction;
  last_.active = std::move(active);
  last_.kkt_residual = residual;
  last_.converged = true;
  last_.iterations = 0;
  last_.seconds = 0.0;
  return report_last(r, s, stats);
}

}  // namespace cdyn
