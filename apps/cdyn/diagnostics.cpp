// diagnostics.cpp — the warnings of a run and the diagnosis of an infeasible start.
#include "diagnostics.hpp"

#include <cmath>
#include <cstdio>

#include "cdyn/base/error.hpp"
#include "cdyn/post/contact_pressure.hpp"

namespace cdyn::app {

namespace {

std::string format(const char* pattern, double a, double b, double c, double d) {
  char text[400];
  std::snprintf(text, sizeof text, pattern, a, b, c, d);
  return text;
}

// dt against the time scale of the model (run_warnings); empty when it is resolved.
std::string time_step_warning(const Simulation& sim) {
  const SceneSpec& s = sim.spec;
  const double dt = sim.dt;
  if (s.physics.model == "oscillator") {
    if (!(s.physics.k > 0.0)) return "";  // free flight: no time scale
    const double scale = std::sqrt(s.physics.m / s.physics.k);
    if (dt <= scale) return "";
    return format("time.dt = %g is %.3g times 1/omega = sqrt(m/k) = %.3g: the oscillation is not resolved "
                  "(%.2g steps a period)",
                  dt, dt / scale, scale, 2.0 * M_PI * scale / dt);
  }
  const bool elastic = s.physics.model == "elasticity";
  const double stiffness = elastic ? s.physics.lame.mu : s.physics.stiffness;
  if (!(stiffness > 0.0) || !(s.physics.rho > 0.0)) return "";
  const double c = std::sqrt(stiffness / s.physics.rho), h = sim.mesh->h_max();
  if (dt * c <= h) return "";
  const char* speed = elastic ? "the shear wave speed sqrt(mu/rho)"
                              : s.physics.model == "bar" ? "sqrt(E/rho)" : "sqrt(tension/rho)";
  // Paoli–Schatzman is explicit (central differences): h/c is about its stability limit.
  const std::string consequence = sim.scheme_name == "paoli_schatzman"
                                      ? "above the stability limit of the explicit paoli_schatzman (about h/c): "
                                        "expect a blow-up"
                                      : "the waves are not resolved in time (fine only for a quasi-static run)";
  return format(("time.dt = %g is %.3g times h/c = %.3g, the time a wave takes to cross the largest cell "
                 "(h = %.3g, c = " + std::string(speed) + "): " + consequence).c_str(),
                dt, dt * c / h, h / c, h);
}

}  // namespace

std::vector<std::string> run_warnings(const Simulation& sim) {
  std::vector<std::string> out = sim.spec.warnings;
  if (std::string w = time_step_warning(sim); !w.empty()) out.push_back(w);
  return out;
}

void infeasible_initial_state(const Simulation& sim, double violation) {
  const std::string by = " (by " + std::to_string(violation) + ")";
  if (sim.has_plane) {
    // The gaps (a + u(a) − p)·n with n reversed: all ≥ 0 means the whole of Γ_C starts
    // on the side the normal points away from.
    const Point n = sim.plane_normal;
    const ContactPressure flipped(sim.problem, sim.contact_parts, sim.plane_point, {-n.x, -n.y});
    const Eigen::VectorXd U = sim.problem.full(sim.initial.U);
    bool feasible = !flipped.vertices().empty();
    for (const ContactPressure::Vertex& a : flipped.vertices()) feasible = feasible && flipped.gap(U, a) >= -1e-12;
    if (feasible) {
      char flip[80];
      std::snprintf(flip, sizeof flip, "[%g, %g]", -n.x + 0.0, -n.y + 0.0);  // + 0.0: no "-0"
      throw InputError("obstacle.normal: the body starts on the wrong side of the plane" + by +
                       "; the normal points from the obstacle into the body's side, and " + flip +
                       " would make the initial state feasible");
    }
  }
  throw InputError("initial.u: the initial state violates the obstacle" + by);
}

}  // namespace cdyn::app
