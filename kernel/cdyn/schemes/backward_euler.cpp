// backward_euler.cpp — backward Euler on the seed's mixed form (eq. 10):
//
//   Bᵀ (V^{n+1} − Vⁿ)/dt + A U^{n+1} = L^{n+1} + Gᵀλ,   C V^{n+1} = B (U^{n+1} − Uⁿ)/dt.
//
// Eliminating V^{n+1} with M = Bᵀ C⁻¹ B and c = 1/dt gives the QP for X = U^{n+1}
//   S = M c² + A,   r = M Uⁿ c² + Bᵀ Vⁿ c + L^{n+1}     (seed eqs. 10–11; docs/schemes.md),
// then V^{n+1} = C⁻¹ B (U^{n+1} − Uⁿ) c.  J never increases (numerical dissipation).
// Rayleigh damping adds α Bᵀ V^{n+1} + β A (U^{n+1} − Uⁿ) c to the first equation, i.e.
// (αM + βA)(U^{n+1} − Uⁿ) c:  S += αc M + βc A,  r += (αc M + βc A) Uⁿ,  and J + W_d
// never increases (docs/schemes.md, "Rayleigh damping").
// Friction (problems/friction.hpp): the step is qp/friction_qp.hpp's (FQP) with X̂ = Uⁿ,
// its slip the step's tangential increment, and J + W_d + W_f never increases
// (docs/friction.md).
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class BackwardEuler final : public StepQPScheme {
 public:
  BackwardEuler(const ConstrainedProblem& p, StepSolver& solver, double dt, const SchemeParameters& parameters)
      : StepQPScheme(p, solver, dt, 1.0, 1.0, parameters.condense, parameters.damping, 1.0, parameters.tol) {}
  std::string name() const override { return "backward_euler"; }

  StepStats step(State& s) override {
    const double c = 1.0 / dt_;
    StepStats stats;
    constrain_at(s.t + dt_);  // U^{n+1} ∈ K̄^h(t^{n+1})
    // (c² + αc) M Uⁿ + c Bᵀ Vⁿ + βc A Uⁿ + L
    Eigen::VectorXd r = evaluated(inertia(c * c + damping_.alpha * c, s.U, c, s.V) + p_.load(s.t + dt_));
    if (damping_.beta > 0.0) r += damping_.beta * c * symmetric_times(p_.A, s.U);
    const Eigen::VectorXd U1 = solve(r, s, stats);
    if (damping_.alpha > 0.0 || damping_.beta > 0.0) stats.dissipated = damping_work(U1 - s.U, dt_);
    s.V = p_.mass->velocity(evaluated(c * (U1 - s.U)));
    s.U = U1;
    s.t += dt_;
    return stats;
  }
};

}  // namespace

std::unique_ptr<TimeScheme> make_backward_euler(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                const SchemeParameters& parameters) {
  return std::make_unique<BackwardEuler>(p, solver, dt, parameters);
}

}  // namespace cdyn
