// paoli_schatzman.cpp — the explicit Paoli–Schatzman scheme with restitution
// coefficient e (seed, slide "Paoli Schatzman scheme"; docs/schemes.md):
//
//   U^{n+1} = −e U^{n−1} + (1 + e) P_K(Yⁿ),
//   Yⁿ = (2Uⁿ − (1 − e) U^{n−1} + dt² M⁻¹(Lⁿ − A Uⁿ)) / (1 + e),
//
// P_K the projection on K̄^h in the M-norm: the QP S = M c², r = M Yⁿ c², which needs
// M but not M⁻¹.  M must be invertible (consistent or lumped mass); for the lumped
// (diagonal) M the projection on the box K̄^h is a clamp, done without a QP.  The
// reported velocity is V^{n+1} = (U^{n+1} − Uⁿ) c and the energy the one central
// differences conserve: ½ V^{n+1}ᵀ M V^{n+1} + ½ U^{n+1}ᵀ A Uⁿ − Lᵀ(U^{n+1} + Uⁿ)/2.
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class PaoliSchatzman final : public StepQPScheme {
 public:
  PaoliSchatzman(const ConstrainedProblem& p, StepSolver& solver, double dt, double e)
      : StepQPScheme(p, solver, dt, 0.0, 1.0), e_(e) {
    remember("U_prev", &U_prev_);
    const SparseMatrix& M = *explicit_mass();
    if (M.nonZeros() == M.rows()) diagonal_ = M.diagonal();
  }
  std::string name() const override { return "paoli_schatzman"; }

  StepStats step(State& s) override {
    const double c = 1.0 / dt_;
    const Eigen::VectorXd F = p_.load(s.t) - p_.A * s.U;  // Lⁿ − A Uⁿ
    // First step: the fictitious U⁻¹ = U⁰ − dt U̇⁰ + ½ dt² M⁻¹(L⁰ − A U⁰) (second-order
    // Taylor; V = U̇ for the classical models this scheme accepts).
    if (U_prev_.size() == 0) U_prev_ = s.U - dt_ * s.V + 0.5 * dt_ * dt_ * p_.mass->acceleration(F);
    const Eigen::VectorXd r = (c * c * mass_times(2.0 * s.U - (1.0 - e_) * U_prev_) + F) / (1.0 + e_);
    StepStats stats;
    constrain_at(s.t + dt_);  // the projection on K̄^h(t^{n+1})
    const Eigen::VectorXd X = diagonal_.size() ? clamp(r, s.t + dt_, s, stats) : solve(r, s, stats);
    const Eigen::VectorXd U1 = (1.0 + e_) * X - e_ * U_prev_;
    U_prev_ = s.U;
    s.V = c * (U1 - s.U);
    s.U = U1;
    s.t += dt_;
    return stats;
  }

  Energy energy(const State& s) const override {
    if (U_prev_.size() == 0) return StepQPScheme::energy(s);  // before the first step
    // ½ U^{n+1}ᵀ A Uⁿ − Lᵀ(U^{n+1} + Uⁿ)/2 on the full fields (Dirichlet values included).
    const Eigen::VectorXd U1 = p_.full(s.U), U0 = p_.full(U_prev_);
    const Eigen::VectorXd& L = p_.full_load(s.t);
    return {p_.mass->kinetic_energy(s.V), 0.5 * U1.dot(p_.A_full * U0) - 0.5 * L.dot(U1 + U0)};
  }

 private:
  // The M-projection on a box for a diagonal M: X = clamp(Y), Y = r/(diag(M) c²), on
  // the bounds at time t.
  Eigen::VectorXd clamp(const Eigen::VectorXd& r, double t, State& s, StepStats& stats) const {
    const Eigen::VectorXd D = diagonal_ / (dt_ * dt_);
    Eigen::VectorXd lower, upper;
    p_.bounds(t, lower, upper);
    const Eigen::VectorXd X = (r.cwiseQuotient(D)).cwiseMax(lower).cwiseMin(upper);
    s.reaction = D.cwiseProduct(X) - r;  // S X − r = Gᵀλ
    for (int i : p_.constrained)
      if (X[i] == lower[i] || X[i] == upper[i]) ++stats.active;
    return X;
  }

  double e_;
  Eigen::VectorXd diagonal_;  // diag(M) when M is diagonal (lumped), else empty
  Eigen::VectorXd U_prev_;    // U^{n−1}
};

}  // namespace

std::unique_ptr<TimeScheme> make_paoli_schatzman(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                 double restitution) {
  if (!(restitution >= 0.0 && restitution <= 1.0))
    throw InputError("restitution", "the restitution coefficient e must lie in [0, 1] (got " +
                     std::to_string(restitution) + ")");
  if (!p.mass->velocity_is_rate() || !p.mass->is_invertible())
    throw InputError("scheme", "paoli_schatzman needs an invertible mass matrix in W^h (the consistent or lumped "
                               "mass), not " + p.mass->name());
  return std::make_unique<PaoliSchatzman>(p, solver, dt, restitution);
}

}  // namespace cdyn
