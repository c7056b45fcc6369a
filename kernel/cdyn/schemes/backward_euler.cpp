// backward_euler.cpp — backward Euler on the seed's mixed form (eq. 10):
//
//   Bᵀ (V^{n+1} − Vⁿ)/dt + A U^{n+1} = L^{n+1} + Gᵀλ,   C V^{n+1} = B (U^{n+1} − Uⁿ)/dt.
//
// Eliminating V^{n+1} with M = Bᵀ C⁻¹ B and c = 1/dt gives the QP for X = U^{n+1}
//   S = M c² + A,   r = M Uⁿ c² + Bᵀ Vⁿ c + L^{n+1}     (seed eqs. 10–11; docs/schemes.md),
// then V^{n+1} = C⁻¹ B (U^{n+1} − Uⁿ) c.  J never increases (numerical dissipation).
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class BackwardEuler final : public StepQPScheme {
 public:
  BackwardEuler(const ConstrainedProblem& p, StepSolver& solver, double dt, bool condense)
      : StepQPScheme(p, solver, dt, 1.0, 1.0, condense) {}
  std::string name() const override { return "backward_euler"; }

  StepStats step(State& s) override {
    const double c = 1.0 / dt_;
    StepStats stats;
    constrain_at(s.t + dt_);  // U^{n+1} ∈ K̄^h(t^{n+1})
    const Eigen::VectorXd r = inertia(c * c, s.U, c, s.V) + p_.load(s.t + dt_);  // c² M Uⁿ + c Bᵀ Vⁿ + L
    const Eigen::VectorXd U1 = solve(r, s, stats);
    s.V = p_.mass->velocity(c * (U1 - s.U));
    s.U = U1;
    s.t += dt_;
    return stats;
  }
};

}  // namespace

std::unique_ptr<TimeScheme> make_backward_euler(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                bool condense) {
  return std::make_unique<BackwardEuler>(p, solver, dt, condense);
}

}  // namespace cdyn
