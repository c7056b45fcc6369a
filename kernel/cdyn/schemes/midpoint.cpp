// midpoint.cpp — the midpoint rule on the seed's mixed form (eq. 10), with the
// constraint either on the half step (as in the seed's experiments) or at the end:
//
//   Bᵀ (V^{n+1} − Vⁿ)/dt + A U^{n+½} = L^{n+½} + Gᵀλ,   C V^{n+½} = B (U^{n+1} − Uⁿ)/dt,
//   U^{n+½} = (Uⁿ + U^{n+1})/2,  V^{n+½} = (Vⁿ + V^{n+1})/2,  c = 1/dt.
//
// midpoint (X = U^{n+½}, constrained):  S = 4 M c² + A,  r = 4 M Uⁿ c² + 2 Bᵀ Vⁿ c + L,
//     then U^{n+1} = 2 U^{n+½} − Uⁿ.
// midpoint_end (X = U^{n+1}, constrained): S = 2 M c² + A/2,
//     r = 2 M Uⁿ c² + 2 Bᵀ Vⁿ c − A Uⁿ/2 + L.
// Both end with C (Vⁿ + V^{n+1})/2 = B (U^{n+1} − Uⁿ) c.  Without active constraints
// the rule conserves J exactly: J^{n+1} − Jⁿ = (U^{n+1} − Uⁿ)ᵀ Gᵀλ (docs/schemes.md).
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class Midpoint final : public StepQPScheme {
 public:
  Midpoint(const ConstrainedProblem& p, StepSolver& solver, double dt, bool constraint_at_end, bool condense)
      : StepQPScheme(p, solver, dt, constraint_at_end ? 0.5 : 1.0, constraint_at_end ? 2.0 : 4.0, condense),
        at_end_(constraint_at_end) {}
  std::string name() const override { return at_end_ ? "midpoint_end" : "midpoint"; }

  StepStats step(State& s) override {
    const double c = 1.0 / dt_;
    const Eigen::VectorXd& L = p_.load(s.t + 0.5 * dt_);
    StepStats stats;
    Eigen::VectorXd U1;
    if (at_end_) {  // 2c² M Uⁿ + 2c Bᵀ Vⁿ − ½ A Uⁿ + L
      U1 = solve(inertia(2 * c * c, s.U, 2 * c, s.V) - 0.5 * (p_.A * s.U) + L, s, stats);
    } else {        // 4c² M Uⁿ + 2c Bᵀ Vⁿ + L
      U1 = 2.0 * solve(inertia(4 * c * c, s.U, 2 * c, s.V) + L, s, stats) - s.U;
    }
    s.V = 2.0 * p_.mass->velocity(c * (U1 - s.U)) - s.V;
    s.U = U1;
    s.t += dt_;
    return stats;
  }

 private:
  bool at_end_;
};

}  // namespace

std::unique_ptr<TimeScheme> make_midpoint(const ConstrainedProblem& p, StepSolver& solver, double dt, bool condense) {
  return std::make_unique<Midpoint>(p, solver, dt, false, condense);
}

std::unique_ptr<TimeScheme> make_midpoint_end(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                              bool condense) {
  return std::make_unique<Midpoint>(p, solver, dt, true, condense);
}

}  // namespace cdyn
