// exact_solution.hpp — the analytic solution a scene may name (`exact.solution`), so
// that a run reports its error against it (summary.json's `error_exact`, which
// `cdyn study` uses as the error of the run; docs/outputs.md).
//
// Available: the two bar impacts of kernel/cdyn/bar_exact.hpp, their parameters taken
// from the scene (physics.E, physics.rho, mesh.length, the initial data and the gap);
// the scene's initial data must be the solution's at t = 0, else the key is refused.
#pragma once

#include <functional>
#include <optional>

#include "simulation.hpp"

namespace cdyn::app {

// u(x, t) of the solution the scene names, or nothing without `exact.solution`.
// InputError for an unknown name or data that do not match the solution.
std::optional<std::function<double(double x, double t)>> exact_displacement(const Simulation& sim);

// ‖u_h(T) − u(T)‖_L2 over the mesh, u_h the full field of the state.
double l2_error_at(const Simulation& sim, const std::function<double(double, double)>& u, const State& s);

}  // namespace cdyn::app
