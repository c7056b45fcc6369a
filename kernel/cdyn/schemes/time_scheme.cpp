// schemes/time_scheme.cpp — choosing a scheme by name; the initial velocity.
#include "cdyn/schemes/time_scheme.hpp"

#include <algorithm>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/schemes/full_step.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

std::string to_string(FullSteps f) {
  switch (f) {
    case FullSteps::Solved: return "solved";
    case FullSteps::Reconstructed: return "reconstructed";
    case FullSteps::Extrapolated: return "extrapolated";
  }
  return "?";
}

std::vector<std::string> time_scheme_names() {
  return {"backward_euler", "midpoint", "midpoint_end", "newmark", "paoli_schatzman", "energy_conserving",
          "discrete_gradient"};
}

namespace {

// Rayleigh damping: α, β ≥ 0 and finite, and a scheme whose step takes it (the one-step
// schemes of docs/schemes.md, "Rayleigh damping"; newmark, paoli_schatzman and the
// three-level energy_conserving have their own identities, not extended to it).
void check_damping(const std::string& name, const RayleighDamping& d) {
  for (double c : {d.alpha, d.beta})
    if (!(c >= 0.0) || !std::isfinite(c))
      throw InputError("damping", "the Rayleigh coefficients must be finite and ≥ 0 (got " + to_text(c) + ")");
  const std::vector<std::string> known = time_scheme_names();
  if (!d.active() || std::find(known.begin(), known.end(), name) == known.end()) return;  // (an unknown name: below)
  for (const char* damped : {"backward_euler", "midpoint", "midpoint_end", "discrete_gradient"})
    if (name == damped) return;
  throw InputError("damping", name + " takes no damping (Rayleigh damping is in backward_euler, midpoint, "
                                     "midpoint_end and discrete_gradient)");
}

}  // namespace

std::unique_ptr<TimeScheme> make_time_scheme(const std::string& name, const ConstrainedProblem& problem,
                                             StepSolver& solver, double dt, const SchemeParameters& parameters) {
  check_damping(name, parameters.damping);
  // Friction is in the one-step schemes whose step unknown is U^{n+1} (docs/friction.md).
  // (on a share of the QP: friction nodes on any rank's cells, so that every rank refuses)
  const bool friction = solver.largest(problem.friction.empty() ? 0.0 : 1.0) > 0.0;
  if (friction && name != "backward_euler" && name != "midpoint_end" && name != "midpoint") {
    const std::vector<std::string> known = time_scheme_names();
    if (std::find(known.begin(), known.end(), name) != known.end())
      throw InputError("scheme", name + " takes no friction (nodal friction is in backward_euler, and in midpoint_end "
                                        "with a mass without massless modes)");
  }
  // A share of the step QP (each rank its cells, StepSolver::solves_a_share): the schemes
  // whose every step is sums over cells and the one summed QP (and the full-step
  // reconstruction's, friction's semismooth Newton iteration and the discrete gradient's
  // energy iteration, which agree over the ranks); the others are not checked.
  if (solver.solves_a_share() && name != "backward_euler" && name != "midpoint" && name != "midpoint_end" &&
      name != "discrete_gradient")
    throw InputError("scheme", name + " does not run on subdomains yet (backward_euler, midpoint, midpoint_end and "
                                      "discrete_gradient do)");
  const bool c = parameters.condense;
  if (name == "backward_euler") return make_backward_euler(problem, solver, dt, parameters);
  if (name == "midpoint") return make_midpoint(problem, solver, dt, parameters);
  if (name == "midpoint_end") return make_midpoint_end(problem, solver, dt, parameters);
  if (name == "discrete_gradient") return make_discrete_gradient(problem, solver, dt, parameters);
  if (name == "newmark") return make_newmark(problem, solver, dt, parameters.beta, parameters.gamma, c);
  if (name == "paoli_schatzman") return make_paoli_schatzman(problem, solver, dt, parameters.restitution);
  if (name == "energy_conserving") return make_energy_conserving(problem, solver, dt, c);
  std::string known;
  for (const auto& n : time_scheme_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("scheme", "unknown scheme '" + name + "' (available: " + known + ")");
}

std::string recommended_scheme(const ConstrainedProblem& problem) {
  if (!problem.friction.empty())  // (docs/friction.md)
    return problem.mass->is_invertible() ? "midpoint_end" : "backward_euler";
  return FullStepReconstruction(problem, 1e-10).needed() ? "discrete_gradient" : "midpoint_end";
}

Eigen::VectorXd initial_velocity(const ConstrainedProblem& problem, const Eigen::VectorXd& Udot0) {
  return problem.mass->velocity(Udot0);
}

}  // namespace cdyn
