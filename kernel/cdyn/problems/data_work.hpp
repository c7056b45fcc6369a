// problems/data_work.hpp — the work done on the body by data that depend on t.
//
// With a load L(t) or an obstacle that moves (K̄^h(t)) the energy J = ½VᵀCV + ½UᵀAU −
// L(t)ᵀU is not conserved: along a solution dJ/dt = −L'(t)·U + λ·g'(t), the power of
// the load and of the obstacle (λ the reaction, g the bound it pushes against; for the
// reduced potential Ψ of eq. (14) this is the envelope theorem, ∂ₜΨ at the minimizer).
// Over a step the midpoint quadrature with the data's increments,
//     W = −(L(t^{n+1}) − L(tⁿ))·U^{n+½} + λ·(g(t^{n+1}) − g(tⁿ)),
// is second order, and exact for data affine in t on a step without a switch of the
// active set.  The discrete gradient scheme balances J against it exactly; for the
// others it is the work a report subtracts from J's drift.
#pragma once

#include <Eigen/Dense>

#include "cdyn/problems/constrained_problem.hpp"

namespace cdyn {

// Whether any datum depends on t (else J is conserved by the semi-discrete problem).
inline bool has_data_in_t(const ConstrainedProblem& p) { return !p.load_is_constant || !p.bounds_are_constant(); }

// The increments of the data over a step: L(t₁) − L(t₀) on all dofs and g(t₁) − g(t₀)
// of the lower and upper bounds (0 where a bound is infinite).  Empty when the datum
// does not depend on t.
struct DataIncrement {
  Eigen::VectorXd dL, dlower, dupper;

  // W = −ΔL·U^{n+½} + λ·Δg, for the free unknowns X = U^{n+½} and the reaction λ on
  // them (λ > 0 pushes against the lower bound, λ < 0 against the upper one).
  double work(const ConstrainedProblem& p, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction) const;
};

DataIncrement data_increment(const ConstrainedProblem& p, double t0, double t1);

}  // namespace cdyn
