// diagnostics.hpp — what a run warns about, and what an infeasible initial state is
// blamed on (docs/scenes.md, "Warnings").
//
// A scene can be valid and still not mean what it says: a step so large that the
// waves (or the oscillation) are not resolved at all, a T that is no multiple of dt.
// Those runs go ahead, with a warning printed on stderr and listed in summary.json.
#pragma once

#include <string>
#include <vector>

#include "simulation.hpp"

namespace cdyn::app {

// The scene's warnings (SceneSpec::warnings) and the time step against the time scale
// of the model: h/c, the time a wave takes to cross the largest cell (c = √(κ/ρ) for
// the bar and the membrane, the shear wave speed √(μ/ρ) for elasticity, the slowest
// wave), or 1/ω = √(m/k) for the oscillator.  A step above it resolves nothing of the
// dynamics (fine for a quasi-static run, as the Hertz scene's).
std::vector<std::string> run_warnings(const Simulation& sim);

// After the run: a warning when the boundary went into an obstacle (max_penetration,
// the whole boundary against every obstacle) deeper than the constrained vertices did
// (max_violation): a part of the body not in `where`, or a vertex held by another
// obstacle, passed through.  Empty otherwise.
std::string penetration_warning(const Simulation& sim, double max_penetration, double max_violation);

// Throws the InputError for an initial state that violates the obstacle by
// `violation`.  It names initial.u, or the normal of a plane (obstacle.normal,
// obstacles[k].normal) when all the plane's contact vertices lie on its other side:
// flipping the normal would make the state feasible (the normal points from the
// obstacle into the body's side).
[[noreturn]] void infeasible_initial_state(const Simulation& sim, double violation);

}  // namespace cdyn::app
