// newmark.cpp — Newmark's (β, γ) scheme in momentum form, so that a singular M (mixed
// pairs, redistributed mass) is allowed (docs/schemes.md):
//
//   C⁻¹B U^{n+1} = C⁻¹B Uⁿ + dt Vⁿ + dt² [(½ − β) V̇ⁿ + β V̇^{n+1}],        (N1)
//   V^{n+1}      = Vⁿ + dt [(1 − γ) V̇ⁿ + γ V̇^{n+1}],                       (N2)
//   Bᵀ V̇^{n+1} + A U^{n+1} = L^{n+1} + Gᵀλ^{n+1},                          (N3)
//
// with V the velocity and V̇ the acceleration, both in H^h (Bᵀ V̇ = M Ü is the inertia
// force of seed eq. 16; A is the stiffness, as everywhere).  Eliminating V̇^{n+1} gives
// the QP for X = U^{n+1}, c = 1/dt:
//   S = M c²/β + A,   r = M Uⁿ c²/β + Bᵀ (Vⁿ c/β + (½ − β)/β V̇ⁿ) + L^{n+1}.
// β = ¼, γ = ½ (the default, the trapezoidal rule) conserves J without contact.
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class Newmark final : public StepQPScheme {
 public:
  Newmark(const ConstrainedProblem& p, StepSolver& solver, double dt, double beta, double gamma, bool condense)
      : StepQPScheme(p, solver, dt, 1.0, 1.0 / beta, condense), beta_(beta), gamma_(gamma) {
    remember("Vdot", &Vdot_);
  }
  std::string name() const override { return "newmark"; }

  StepStats step(State& s) override {
    const double c = 1.0 / dt_, b = beta_;
    // V̇⁰ from (N3) at t = 0 with λ⁰ = 0: Bᵀ V̇⁰ = L⁰ − A U⁰.
    if (Vdot_.size() == 0) Vdot_ = p_.mass->acceleration(p_.load(s.t) - p_.A * s.U);
    StepStats stats;
    constrain_at(s.t + dt_);  // U^{n+1} ∈ K̄^h(t^{n+1})
    const Eigen::VectorXd r =  // (c²/β) M Uⁿ + Bᵀ((c/β) Vⁿ + ((½ − β)/β) V̇ⁿ) + L
        inertia(c * c / b, s.U, 1.0, (c / b) * s.V + ((0.5 - b) / b) * Vdot_) + p_.load(s.t + dt_);
    const Eigen::VectorXd U1 = solve(r, s, stats);
    // (N1) for V̇^{n+1}, then (N2) for V^{n+1}.
    const Eigen::VectorXd Vdot1 = (p_.mass->velocity(c * c * (U1 - s.U)) - c * s.V - (0.5 - b) * Vdot_) / b;
    s.V += dt_ * ((1.0 - gamma_) * Vdot_ + gamma_ * Vdot1);
    Vdot_ = Vdot1;
    s.U = U1;
    s.t += dt_;
    return stats;
  }

 private:
  double beta_, gamma_;
  Eigen::VectorXd Vdot_;  // V̇ⁿ, the acceleration in H^h (empty before the first step)
};

}  // namespace

std::unique_ptr<TimeScheme> make_newmark(const ConstrainedProblem& p, StepSolver& solver, double dt, double beta,
                                         double gamma, bool condense) {
  if (!(beta > 0.0 && beta <= 0.5)) throw InputError("beta", "Newmark's β must lie in (0, ½] (got " + to_text(beta) + ")");
  if (!(gamma >= 0.5 && gamma <= 1.0)) throw InputError("gamma", "Newmark's γ must lie in [½, 1] (got " + to_text(gamma) + ")");
  return std::make_unique<Newmark>(p, solver, dt, beta, gamma, condense);
}

}  // namespace cdyn
