// energy_conserving.cpp — the seed's energy-conserving three-level scheme, with
// the contact condition written on the velocity (seed, slide "An energy conserving
// scheme"; docs/schemes.md):
//
//   M (U^{n+1} − 2Uⁿ + U^{n−1}) c² + A (U^{n+1} + 2Uⁿ + U^{n−1})/4 = Lⁿ + Gᵀλⁿ,
//   Vⁿ = (U^{n+1} − U^{n−1}) c/2;  a node in contact at tⁿ (Gᵢ Uⁿ ≥ αᵢ) has
//   Gᵢ Vⁿ ≤ 0, λⁿᵢ ≤ 0, λⁿᵢ Gᵢ Vⁿ = 0;  every other node λⁿᵢ = 0.
//
// QP for X = U^{n+1}: S = M c² + A/4, r = M (2Uⁿ − U^{n−1}) c² − A (2Uⁿ + U^{n−1})/4 + Lⁿ,
// and for cdyn's bounds u ≥ g the contact condition is the bound U^{n+1}ᵢ ≥ U^{n−1}ᵢ on
// the dofs with Uⁿᵢ ≤ gᵢ.  E^{n+½} = ½|(U^{n+1} − Uⁿ)c|²_M + ½ŪᵀAŪ − LᵀŪ, Ū the mean
// of U^{n+1} and Uⁿ, is conserved exactly, contact or not; the position constraint is
// only enforced through the velocity, so an O(dt·v) interpenetration remains.
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class EnergyConserving final : public StepQPScheme {
 public:
  EnergyConserving(const ConstrainedProblem& p, StepSolver& solver, double dt, bool condense)
      : StepQPScheme(p, solver, dt, 0.25, 1.0, condense) {
    remember("U_prev", &U_prev_);
  }
  std::string name() const override { return "energy_conserving"; }

  StepStats step(State& s) override {
    const double c = 1.0 / dt_;
    StepStats stats;
    Eigen::VectorXd U1;
    if (U_prev_.size() == 0) {
      // Start: one midpoint step, constraint on the half step.  Its matrix 4Mc² + A is
      // 4S, so the scheme's own QP serves with r = M U⁰ c² + ½ Bᵀ V⁰ c + L^{½}/4.
      const Eigen::VectorXd r = inertia(c * c, s.U, 0.5 * c, s.V) + 0.25 * p_.load(s.t + 0.5 * dt_);
      U1 = 2.0 * solve(r, s, stats) - s.U;
      s.reaction *= 4.0;  // the midpoint step's Gᵀλ (its QP was scaled by ¼)
    } else {
      const auto [lower, upper] = velocity_bounds(s.U);
      set_bounds(lower, upper);
      const Eigen::VectorXd r = c * c * mass_times(2.0 * s.U - U_prev_) - 0.25 * symmetric_times(p_.A, 2.0 * s.U + U_prev_) +
                                p_.load(s.t);
      U1 = solve(r, s, stats);
    }
    U_prev_ = s.U;
    s.V = p_.mass->velocity(c * (U1 - s.U));
    s.U = U1;
    s.t += dt_;
    return stats;
  }

  // E^{n+½}: kinetic ½ VᵀCV of V = C⁻¹B (U^{n+1} − Uⁿ) c, potential at Ū = (U^{n+1} + Uⁿ)/2.
  Energy energy(const State& s) const override {
    if (U_prev_.size() == 0) return StepQPScheme::energy(s);  // before the first step
    return {p_.mass->kinetic_energy(s.V), p_.potential_energy(0.5 * (s.U + U_prev_), s.t - 0.5 * dt_)};
  }

 private:
  // The bounds of step n: U^{n+1}ᵢ ≥ U^{n−1}ᵢ where Uⁿᵢ ≤ lowerᵢ (and symmetrically for
  // upper bounds); no bound elsewhere.
  std::pair<Eigen::VectorXd, Eigen::VectorXd> velocity_bounds(const Eigen::VectorXd& U) const {
    const double inf = std::numeric_limits<double>::infinity();
    Eigen::VectorXd lower = Eigen::VectorXd::Constant(U.size(), -inf), upper = Eigen::VectorXd::Constant(U.size(), inf);
    for (int i : p_.constrained) {
      if (U[i] <= p_.lower[i]) lower[i] = U_prev_[i];
      if (U[i] >= p_.upper[i]) upper[i] = U_prev_[i];
    }
    return {lower, upper};
  }

  Eigen::VectorXd U_prev_;  // U^{n−1} (empty before the first step)
};

}  // namespace

std::unique_ptr<TimeScheme> make_energy_conserving(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                   bool condense) {
  // A massless mode z ∈ Ker M obeys zᵀA (U^{n+1} + 2Uⁿ + U^{n−1})/4 = zᵀL: the double
  // root −1 of x² + 2x + 1 lets it grow like (−1)ⁿ n (measured: P1+/P0 and P2/P1 on the
  // membrane sink by 0.3 in 800 steps).  So M must be invertible.
  // Its contact condition is written on the velocity relative to a fixed obstacle
  // (G Vⁿ ≤ 0); a moving one would need the obstacle's velocity in it.
  if (!p.bounds_are_constant())
    throw InputError("scheme", "energy_conserving takes fixed obstacles only (its contact condition is G V ≤ 0); "
                               "use discrete_gradient or midpoint with a moving obstacle");
  if (!p.mass->is_invertible())
    throw InputError("scheme", "energy_conserving needs an invertible mass matrix (its massless modes are unstable): "
                               "the consistent or lumped mass, or a pair with Ker B = {0} such as P1/P1 — not " +
                               p.mass->name());
  return std::make_unique<EnergyConserving>(p, solver, dt, condense);
}

}  // namespace cdyn
