// midpoint.cpp — the midpoint rule on the seed's mixed form (eq. 10), with the
// constraint either on the half step (as in the seed's experiments) or at the end:
//
//   Bᵀ (V^{n+1} − Vⁿ)/dt + A U^{n+½} = L^{n+½} + Gᵀλ,   C V^{n+½} = B (U^{n+1} − Uⁿ)/dt,
//   U^{n+½} = (Uⁿ + U^{n+1})/2,  V^{n+½} = (Vⁿ + V^{n+1})/2,  c = 1/dt.
//
// midpoint (X = U^{n+½}, constrained):  S = 4 M c² + A,  r = 4 M Uⁿ c² + 2 Bᵀ Vⁿ c + L,
//     then B U^{n+1} = B (2 U^{n+½} − Uⁿ).
// midpoint_end (X = U^{n+1}, constrained): S = 2 M c² + A/2,
//     r = 2 M Uⁿ c² + 2 Bᵀ Vⁿ c − A Uⁿ/2 + L.
// Both end with C (Vⁿ + V^{n+1})/2 = B (U^{n+1} − Uⁿ) c.  Without active constraints
// the rule conserves J exactly: J^{n+1} − Jⁿ = (U^{n+1} − Uⁿ)ᵀ Gᵀλ (docs/schemes.md).
//
// Rayleigh damping adds α Bᵀ V^{n+½} + β A (U^{n+1} − Uⁿ) c = (αM + βA)(U^{n+1} − Uⁿ) c
// to the first equation: with U^{n+1} − Uⁿ = 2 (X − Uⁿ) (midpoint) or X − Uⁿ
// (midpoint_end), S gains (2c or c)(αM + βA) and r the same times Uⁿ, and
// J^{n+1} + W_d − Jⁿ = (U^{n+1} − Uⁿ)ᵀ Gᵀλ with W_d = (U^{n+1} − Uⁿ)ᵀ(αM + βA)(U^{n+1} − Uⁿ) c.
//
// The massless part of U^{n+1} (Ker B) is not what the extrapolation 2U^{n+½} − Uⁿ (or
// midpoint_end's QP, which balances it at the midpoint) leaves: it solves the static
// problem (14) at t^{n+1}, computed after the step by FullStepReconstruction (P1+/P0,
// P1+/P1, P2/P1, the redistributed mass; schemes/full_step.hpp).  The
// step reads Uⁿ only through B Uⁿ, so this changes the reported state, not the dynamics.
//
// Friction (problems/friction.hpp): midpoint_end only, with a mass that has no massless
// mode; the step is qp/friction_qp.hpp's (FQP) with X̂ = Uⁿ, and
// J^{n+1} + W_d + W_f − Jⁿ = (U^{n+1} − Uⁿ)_Nᵀ λ_N exactly (docs/friction.md).
#include <optional>
#include <string>

#include "cdyn/base/error.hpp"

#include "cdyn/linalg/parallel.hpp"
#include "cdyn/schemes/full_step.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class Midpoint final : public StepQPScheme {
 public:
  Midpoint(const ConstrainedProblem& p, StepSolver& solver, double dt, bool constraint_at_end,
           const SchemeParameters& parameters)
      : StepQPScheme(p, solver, dt, constraint_at_end ? 0.5 : 1.0, constraint_at_end ? 2.0 : 4.0, parameters.condense,
                     parameters.damping, constraint_at_end ? 1.0 : 2.0, parameters.tol),
        at_end_(constraint_at_end) {
    full_step_.emplace(p, parameters.tol, false,
                       parameters.reconstruct_by_cg ? FullStepReconstruction::Solves::CgOnly
                                                    : FullStepReconstruction::Solves::Mixed,
                       &solver);
    if (!full_step_->available() || (full_step_->needed() && !parameters.reconstruct)) full_step_.reset();
    // Friction: eq. (14) has no friction term, so a reconstructed massless part would
    // slide freely; only a mass with no massless mode (Ker M = {0}: nothing to
    // reconstruct) keeps the frictional step's U^{n+1} as it is (docs/friction.md).
    if (with_friction() && (!at_end_ || !p.mass->is_invertible()))
      throw InputError("scheme", std::string(at_end_ ? "midpoint_end" : "midpoint") +
                                     " with friction needs a mass without massless modes (P1/P1, P1/P0, consistent, "
                                     "lumped) and the constraint at the end of the step: use midpoint_end with such a "
                                     "mass, or backward_euler");
  }
  std::string name() const override { return at_end_ ? "midpoint_end" : "midpoint"; }

  FullSteps full_steps() const override {
    if (!full_step_) return FullSteps::Extrapolated;
    return full_step_->needed() ? FullSteps::Reconstructed : FullSteps::Solved;
  }

  void initialize(State& s) override {
    initialized_ = true;
    if (full_step_) s.U = (*full_step_)(s.U, s.t);
  }

  SchemeMemory memory() const override {
    SchemeMemory m = StepQPScheme::memory();
    if (full_step_) full_step_->store(m);
    return m;
  }

  void restore(const SchemeMemory& m) override {
    StepQPScheme::restore(m);
    if (full_step_) full_step_->restore(m);
    initialized_ = true;  // the state that goes with m has its massless part already
  }

  StepStats step(State& s) override {
    if (!initialized_) initialize(s);
    const double c = 1.0 / dt_;
    constrain_at(at_end_ ? s.t + dt_ : s.t + 0.5 * dt_);  // the constrained unknown's time level
    const Eigen::VectorXd& L = p_.load(s.t + 0.5 * dt_);
    StepStats stats;
    const double alpha = damping_.alpha, beta = damping_.beta;
    Eigen::VectorXd U1;
    if (at_end_) {  // (2c² + αc) M Uⁿ + 2c Bᵀ Vⁿ + (βc − ½) A Uⁿ + L
      U1 = solve(inertia(2 * c * c + alpha * c, s.U, 2 * c, s.V) + (beta * c - 0.5) * symmetric_times(p_.A, s.U) + L, s, stats);
    } else {        // (4c² + 2αc) M Uⁿ + 2c Bᵀ Vⁿ + 2βc A Uⁿ + L
      Eigen::VectorXd r = evaluated(inertia(4 * c * c + 2 * alpha * c, s.U, 2 * c, s.V) + L);
      if (beta > 0.0) r += 2 * beta * c * symmetric_times(p_.A, s.U);
      U1 = evaluated(2.0 * solve(r, s, stats) - s.U);
    }
    if (alpha > 0.0 || beta > 0.0) stats.dissipated = damping_work(U1 - s.U, dt_);
    s.V = evaluated(2.0 * p_.mass->velocity(evaluated(c * (U1 - s.U))) - s.V);
    s.t += dt_;
    if (!full_step_) {
      s.U = U1;
      return stats;
    }
    s.U = (*full_step_)(U1, s.t, &stats.reconstruction_kkt);
    stats.reconstruction_seconds = full_step_->last_cost().seconds;
    stats.reconstruction_iterations = full_step_->last_cost().qp_iterations;
    return stats;
  }

 private:
  bool at_end_;
  bool initialized_ = false;
  std::optional<FullStepReconstruction> full_step_;
};

}  // namespace

std::unique_ptr<TimeScheme> make_midpoint(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                          const SchemeParameters& parameters) {
  return std::make_unique<Midpoint>(p, solver, dt, false, parameters);
}

std::unique_ptr<TimeScheme> make_midpoint_end(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                              const SchemeParameters& parameters) {
  return std::make_unique<Midpoint>(p, solver, dt, true, parameters);
}

}  // namespace cdyn
