// exact_solution.cpp — scene keys → the bar impact solutions; the L2 error of a state.
#include "exact_solution.hpp"

#include <cmath>

#include "cdyn/exact/bar_exact.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fe/norms.hpp"

namespace cdyn::app {

namespace {

// The scene's initial displacement and velocity must be the solution's at t = 0
// (checked at the vertices and mid-cells to 1e-12).
void check_initial_data(const SceneSpec& s, const Mesh& mesh, const std::function<double(double, double)>& u) {
  const Field& u0 = s.initial.u[0].field;
  const double L = s.mesh.length;
  const int n = 2 * mesh.n_cells();
  for (int i = 0; i <= n; ++i) {
    const double x = L * i / n;
    if (std::abs(u0(Point{x}, 0.0) - u(x, 0.0)) > 1e-12)
      throw InputError("exact.solution: initial.u differs from the named solution at x = " + std::to_string(x));
  }
}

}  // namespace

std::optional<std::function<double(double, double)>> exact_displacement(const Simulation& sim) {
  const SceneSpec& s = sim.spec;
  if (s.exact_solution.empty()) return std::nullopt;
  const std::string& name = s.exact_solution;
  if (sim.model != "bar") throw InputError("exact.solution: '" + name + "' needs physics.model = \"bar\"");
  const double E = s.physics.stiffness, rho = s.physics.rho, L = s.mesh.length;
  const double g = s.obstacle.g.field(Point{}, 0.0);
  std::function<double(double, double)> u;
  if (name == "clamped_bar") {
    if (std::abs(g) > 0.0) throw InputError("exact.solution: clamped_bar has its obstacle at g = 0");
    ClampedBarImpact b{E, rho, L, s.initial.u[0].field(Point{}, 0.0)};
    u = [b](double x, double t) { return b.displacement(x, t); };
  } else if (name == "falling_bar") {
    FallingBar b{E, rho, L, -s.initial.v[0].field(Point{}, 0.0), -g};
    if (!(b.v0 > 0.0 && b.d > 0.0)) throw InputError("exact.solution: falling_bar needs initial.v < 0 and obstacle.g < 0");
    u = [b](double x, double t) { return b.displacement(x, t); };
  } else {
    throw InputError("exact.solution: unknown solution '" + name + "' (clamped_bar, falling_bar)");
  }
  check_initial_data(s, *sim.mesh, u);
  return u;
}

double l2_error_at(const Simulation& sim, const std::function<double(double, double)>& u, const State& s) {
  const Field field = [&u](double x, double, double t) { return u(x, t); };
  return l2_error(*sim.problem.W, sim.problem.full(s.U), field, s.t);
}

}  // namespace cdyn::app
