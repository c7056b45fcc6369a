// implicit_step.hpp — what the one-step implicit schemes share.
//
// Backward Euler and the two midpoint variants all solve, per step, a QP with
//     S = a A + k M,   k = m / dt²,
// (a, m) = (1, 1), (1, 4) and (½, 2) respectively, and differ only in r and in the
// update.  This base class builds S once (explicitly when M is sparse, in saddle form
// otherwise), keeps the step solver's warm start, and provides M·x for the right-hand
// sides.
#pragma once

#include "cdyn/time_scheme.hpp"

namespace cdyn {

class ImplicitStep : public TimeScheme {
 public:
  // J(Uⁿ, Vⁿ) = ½ Vᵀ C V + ½ UᵀAU − LᵀU of the full field.
  Energy energy(const State& s) const override;

 protected:
  ImplicitStep(const ConstrainedProblem& p, StepSolver& solver, double dt, double a, double m);

  // M x = Bᵀ C⁻¹ B x (sparse product when M is explicit).
  Eigen::VectorXd mass_times(const Eigen::VectorXd& x) const;

  // Solves the step QP with right-hand side r; fills s.reaction and the stats.
  Eigen::VectorXd solve(const Eigen::VectorXd& r, State& s, StepStats& stats);

  // The bounds of the step QP (the problem's K̄^h unless a scheme moves them).
  void set_bounds(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);

  // The explicit M when the mass model has one (H^h = P0, classical models).
  const std::optional<SparseMatrix>& explicit_mass() const { return M_; }

  const ConstrainedProblem& p_;
  StepSolver& solver_;
  double dt_;

 private:
  std::optional<SparseMatrix> M_;
  BoundQP qp_;
  QPResult last_;
  bool has_last_ = false;
};

}  // namespace cdyn

namespace cdyn {
// The schemes built on ImplicitStep (one file each).
std::unique_ptr<TimeScheme> make_backward_euler(const ConstrainedProblem& p, StepSolver& solver, double dt);
std::unique_ptr<TimeScheme> make_midpoint(const ConstrainedProblem& p, StepSolver& solver, double dt);
std::unique_ptr<TimeScheme> make_midpoint_end(const ConstrainedProblem& p, StepSolver& solver, double dt);
std::unique_ptr<TimeScheme> make_newmark(const ConstrainedProblem& p, StepSolver& solver, double dt, double beta,
                                         double gamma);
std::unique_ptr<TimeScheme> make_paoli_schatzman(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                 double restitution);
std::unique_ptr<TimeScheme> make_energy_conserving(const ConstrainedProblem& p, StepSolver& solver, double dt);
}  // namespace cdyn
