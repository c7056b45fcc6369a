// diagnostics.cpp — the warnings of a run and the diagnosis of an infeasible start.
#include "diagnostics.hpp"

#include <cmath>
#include <cstdio>

#include "cdyn/base/error.hpp"

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
  const double c = std::sqrt(stiffness / s.physics.rho), h = sim.whole.h;
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

std::string penetration_warning(const Simulation& sim, double max_penetration, double max_violation) {
  // Beyond round-off of the coordinates: a billionth of the mesh size.
  if (!(max_penetration > max_violation + 1e-9 * sim.whole.h)) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "the boundary went %.3g into an obstacle (max_penetration) where the constrained vertices went %.3g: "
                "a part not in obstacle.where, or a vertex held by another obstacle, passed through "
                "(docs/scenes.md, \"Obstacles\"; obstacle.where = \"boundary\" constrains the whole boundary)",
                max_penetration, max_violation);
  return text;
}

void infeasible_initial_state(const Simulation& sim, double violation) {
  const std::string by = " (by " + std::to_string(violation) + ")";
  const ConstrainedProblem& p = sim.problem;
  const std::vector<SceneSpec::Rigid>& rigid = sim.spec.obstacle.rigid;
  if (sim.has_obstacle && p.obstacles.size() == rigid.size()) {
    // A plane given by its normal (no gap function), all of whose contact vertices start
    // at φ(a + u(a), 0) ≤ 0, some below: the body lies on the side the normal points
    // away from, and the reversed normal would make the start feasible.
    const Eigen::VectorXd U = p.full(sim.initial.U);
    const FESpace& W = *p.W;
    for (std::size_t k = 0; k < rigid.size(); ++k) {
      if (rigid[k].gap) continue;
      bool reversed_feasible = true, violated = false;
      for (const auto& c : p.contact_nodes) {
        if (c.obstacle != static_cast<int>(k)) continue;
        const Point& a = sim.mesh->vertices[c.vertex];
        double x[3] = {a.x, a.y, a.z};
        for (int j = 0; j < W.components(); ++j) x[j] += U[W.vertex_dof(c.vertex, j)];
        const double phi = p.obstacles[k].gap(Point{x[0], x[1], x[2]}, 0.0);
        reversed_feasible = reversed_feasible && phi <= 1e-12;
        violated = violated || phi < -1e-12;
      }
      if (!reversed_feasible || !violated) continue;
      // the normal as given (absent: the default e_y or e_z), reversed
      std::vector<double> n = rigid[k].normal;
      if (n.empty()) n = W.components() == 3 ? std::vector<double>{0, 0, 1} : std::vector<double>{0, 1};
      std::string flip = "[";
      for (std::size_t j = 0; j < n.size(); ++j) {
        char c[40];
        std::snprintf(c, sizeof c, "%s%g", j ? ", " : "", -n[j] + 0.0);  // + 0.0: no "-0"
        flip += c;
      }
      flip += "]";
      throw InputError(rigid[k].key + ".normal: the body starts on the wrong side of the plane" + by +
                       "; the normal points from the obstacle into the body's side, and " + flip +
                       " would make the initial state feasible");
    }
  }
  throw InputError("initial.u: the initial state violates the obstacle" + by);
}

}  // namespace cdyn::app
