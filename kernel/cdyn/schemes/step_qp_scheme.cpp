// step_qp_scheme.cpp — the step QP S = aA + kM, built once and solved with warm starts.
#include "cdyn/schemes/step_qp_scheme.hpp"

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

StepQPScheme::StepQPScheme(const ConstrainedProblem& p, StepSolver& solver, double dt, double a, double m,
                           bool condense, const RayleighDamping& damping, double s)
    : p_(p), solver_(solver), dt_(dt), damping_(damping), condense_(condense), M_(p.mass->matrix()) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw InputError("dt", "must be positive and finite (got " + to_text(dt) + ")");
  if (!M_) {
    const SaddleForm f = p.mass->saddle(SparseMatrix(), 1.0);
    // H^h = W^h (P1/P1): B = C, so M = Bᵀ C⁻¹ B = C, the consistent mass — sparse after
    // all; an explicit S (one Cholesky factor) instead of the saddle form (an LU of a
    // matrix twice the size per active set).
    if (same_matrix(f.B, f.C)) M_ = f.C;
  }
  build(a + s * damping.beta / dt, m + s * damping.alpha * dt);  // + (s/dt)(αM + βA)
}

void StepQPScheme::build(double a, double m) {
  a_ = a;
  m_ = m;
  const double k = m / (dt_ * dt_);
  qp_.lower = p_.lower;
  qp_.upper = p_.upper;
  qp_.saddle.reset();
  condensation_.reset();
  has_last_ = false;
  if (!M_) {
    qp_.S = SparseMatrix();
    qp_.saddle = p_.mass->saddle(SparseMatrix(a_ * p_.A), k);
    return;
  }
  qp_.S = a_ * p_.A + k * *M_;
  qp_.S.makeCompressed();
  if (!condense_) return;
  DiagonalCondensation c(qp_.S, p_.lower, p_.upper);
  if (c.n_condensed() == 0) return;
  qp_.S = c.S_c();  // (c keeps the full S, for set_bounds)
  qp_.lower = c.kept(p_.lower);
  qp_.upper = c.kept(p_.upper);
  condensation_.emplace(std::move(c));
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
  qp_.lower = p_.lower;
  qp_.upper = p_.upper;
  condensation_.reset();
  has_last_ = false;
}

SchemeMemory StepQPScheme::memory() const {
  SchemeMemory m;
  m.numbers["condensed"] = condensation_ ? 1.0 : 0.0;
  store_warm_start(m, "step_qp", last_, has_last_);
  for (const auto& [name, v] : remembered_) m.store_if_any(name, *v);
  return m;
}

void StepQPScheme::restore(const SchemeMemory& m) {
  solver_.clear();
  // a condensation ended by a bound stays ended (set_bounds); the factors a_, m_ are
  // those of a whole step between steps, as build() made them
  if (m.number("condensed") == 0.0 && condensation_) end_condensation();
  has_last_ = load_warm_start(m, "step_qp", last_);
  for (const auto& [name, v] : remembered_) *v = m.vector_or_empty(name);
}

void StepQPScheme::constrain_at(double t) {
  if (p_.bounds_are_constant()) return;
  Eigen::VectorXd lower, upper;
  p_.bounds(t, lower, upper);
  set_bounds(lower, upper);
}

Eigen::VectorXd StepQPScheme::solve(const Eigen::VectorXd& r, State& s, StepStats& stats) {
  qp_.r = condensation_ ? condensation_->reduce(r) : r;  // r_c = r_v − S_vb S_bb⁻¹ r_b
  last_ = solver_.solve(qp_, has_last_ ? &last_ : nullptr);
  has_last_ = true;
  stats.qp_iterations = last_.iterations;
  stats.qp_seconds = last_.seconds;
  stats.active = static_cast<int>(last_.active.size());
  stats.kkt_residual = last_.kkt_residual;
  stats.converged = last_.converged;
  if (!condensation_) {
    s.reaction = last_.reaction;
    return last_.X;
  }
  s.reaction = condensation_->expand_reaction(last_.reaction);  // λ_b = 0
  return condensation_->expand(last_.X, r);                     // X_b = S_bb⁻¹ (r_b − S_bv X_v)
}

}  // namespace cdyn
