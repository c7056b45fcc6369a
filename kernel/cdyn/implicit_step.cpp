// implicit_step.cpp — the step QP S = aA + kM, built once and solved with warm starts.
#include "cdyn/implicit_step.hpp"

#include <cmath>

#include "cdyn/error.hpp"

namespace cdyn {

ImplicitStep::ImplicitStep(const ConstrainedProblem& p, StepSolver& solver, double dt, double a, double m)
    : p_(p), solver_(solver), dt_(dt), M_(p.mass->matrix()) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw InputError("time.dt: must be positive (got " + std::to_string(dt) + ")");
  const double k = m / (dt * dt);
  if (M_) {
    qp_.S = a * p.A + k * *M_;
    qp_.S.makeCompressed();
  } else {
    qp_.saddle = p.mass->saddle(SparseMatrix(a * p.A), k);
  }
  qp_.lower = p.lower;
  qp_.upper = p.upper;
}

Energy ImplicitStep::energy(const State& s) const {
  return {p_.mass->kinetic_energy(s.V), p_.potential_energy(s.U, s.t)};
}

Eigen::VectorXd ImplicitStep::mass_times(const Eigen::VectorXd& x) const {
  if (M_) return *M_ * x;
  return p_.mass->momentum(p_.mass->velocity(x));
}

void ImplicitStep::set_bounds(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  qp_.lower = lower;
  qp_.upper = upper;
}

Eigen::VectorXd ImplicitStep::solve(const Eigen::VectorXd& r, State& s, StepStats& stats) {
  qp_.r = r;
  last_ = solver_.solve(qp_, has_last_ ? &last_ : nullptr);
  has_last_ = true;
  s.reaction = last_.reaction;
  stats.qp_iterations = last_.iterations;
  stats.qp_seconds = last_.seconds;
  stats.active = static_cast<int>(last_.active.size());
  stats.kkt_residual = last_.kkt_residual;
  return last_.X;
}

}  // namespace cdyn
