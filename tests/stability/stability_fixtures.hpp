// stability_fixtures.hpp — what the hard-case tests of tests/stability share: a run
// loop that records the energy, the constraint violation and the QP iteration counts
// of every step, and the 1D bars of exact/bar_exact.hpp as ConstrainedProblems.
//
// Numbers are printed by every test (and collected in docs/stability.md); the
// tolerances are justified where they are asserted.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "../unit/scheme_fixtures.hpp"
#include "cdyn/exact/bar_exact.hpp"

namespace cdyn::stability {

using testing::initial_state;
using testing::kMethods;
using testing::label;
using testing::membrane;
using testing::Method;
using testing::plain;

// What a run of `steps` steps did.
struct RunRecord {
  double J0 = 0.0;           // energy of the initial state
  double J_max = -INFINITY;  // max over the steps of J^n
  double J_min = INFINITY;
  double J_end = 0.0;
  double max_violation = 0.0;  // max over the steps of max(lower − U, 0) on the constrained dofs
  int max_iterations = 0;      // QP iterations of the worst step
  double mean_iterations = 0.0;
  int active_changes = 0;      // steps whose active count differs from the previous step's
  bool finite = true;          // U, V and J stayed finite
  int steps = 0;
  double drift_first_half = 0.0, drift_second_half = 0.0;  // max |J − J0| over each half
  // Σₙ (U^{n+1} − Uⁿ)ᵀ(reaction of step n+1): the work of the contact force.  For both
  // midpoint schemes J^{n+1} − Jⁿ is exactly this step's term (docs/schemes.md), so
  // J_end − J0 − contact_work is the round-off accumulated over the run.
  double contact_work = 0.0;

  double growth() const { return J_max - J0; }  // > 0: J rose above its initial value
};

// Runs `steps` steps of `scheme` from `s` (updated), recording the above.
// (scheme.initialize(s) first: the energy identity starts from the scheme's own U⁰.)
inline RunRecord run(TimeScheme& scheme, const ConstrainedProblem& p, State& s, int steps) {
  scheme.initialize(s);
  RunRecord r;
  r.J0 = scheme.energy(s).total();
  long total_iterations = 0;
  int last_active = -1;
  for (int n = 0; n < steps; ++n) {
    const Eigen::VectorXd Un = s.U;
    const StepStats st = scheme.step(s);
    if (s.reaction.size() == s.U.size()) r.contact_work += (s.U - Un).dot(s.reaction);
    const double J = scheme.energy(s).total();
    r.finite = r.finite && s.U.allFinite() && s.V.allFinite() && std::isfinite(J);
    if (!r.finite) break;
    r.J_max = std::max(r.J_max, J);
    r.J_min = std::min(r.J_min, J);
    r.J_end = J;
    r.max_violation = std::max(r.max_violation, p.max_violation(s.U));
    r.max_iterations = std::max(r.max_iterations, st.qp_iterations);
    total_iterations += st.qp_iterations;
    r.active_changes += last_active >= 0 && st.active != last_active;
    last_active = st.active;
    double& half = 2 * n < steps ? r.drift_first_half : r.drift_second_half;
    half = std::max(half, std::abs(J - r.J0));
    ++r.steps;
  }
  r.mean_iterations = r.steps > 0 ? static_cast<double>(total_iterations) / r.steps : 0.0;
  return r;
}

inline void print(const std::string& what, const RunRecord& r) {
  std::printf("%s: %d steps, J0 = %.6e, max (J - J0)/|J0| = %+.3e, min (J - J0)/|J0| = %+.3e, (J_end - J0)/|J0| = "
              "%+.3e, max violation = %.3e, QP iterations max %d mean %.2f, active-set changes %d%s\n",
              what.c_str(), r.steps, r.J0, r.growth() / std::abs(r.J0), (r.J_min - r.J0) / std::abs(r.J0),
              (r.J_end - r.J0) / std::abs(r.J0), r.max_violation, r.max_iterations, r.mean_iterations,
              r.active_changes, r.finite ? "" : "  NOT FINITE");
}

using testing::tight;

// The 1D bar of data/scenes/bar.toml (docs/bar_impact.md) on [0, L] with n cells:
// E = ρ = 1, Signorini contact at x = 0 (u(0) ≥ g), clamped at x = L (clamped = true)
// or free at both ends.
inline ConstrainedProblem bar(const Mesh& mesh, const Method& m, bool clamped, double g) {
  ScalarWaveData d;
  d.mass = cdyn::MassSpec::parse(m.velocity, m.W);
  d.f = [](double, double, double) { return 0.0; };
  if (clamped) d.dirichlet_parts = {mesh.part_index("right")};
  d.dirichlet_value = [](double, double, double) { return 0.0; };
  d.obstacle_on_all_vertices = false;
  d.obstacle_parts = {mesh.part_index("left")};
  d.obstacle_g = [g](double, double, double) { return g; };
  return build_scalar_wave(mesh, d);
}

// The clamped bar's initial state u = δ(1 − x/L), v = 0 (ClampedBarImpact).
inline State clamped_bar_state(const ConstrainedProblem& p, const ClampedBarImpact& b) {
  State s;
  s.U = p.unknowns(p.W->interpolate([&](double x, double, double) { return b.displacement(x, 0.0); }));
  s.V = initial_velocity(p, Eigen::VectorXd::Zero(p.n_free()));
  return s;
}

// The falling bar's initial state u = 0, u̇ = −v₀ (FallingBar).
inline State falling_bar_state(const ConstrainedProblem& p, const FallingBar& b) {
  State s;
  s.U = Eigen::VectorXd::Zero(p.n_free());
  s.V = initial_velocity(p, p.unknowns(p.W->interpolate([&](double, double, double) { return -b.v0; })));
  return s;
}

}  // namespace cdyn::stability
