// problems/scalar_wave.hpp — the scalar constrained wave problems: the seed's membrane with an
// obstacle (Ω the unit square) and the 1D elastic bar with Signorini contact.
//
//     ρ ü − κ Δu = f   in Ω,      u = g_D on Γ_D,      u(a_i) ≥ g(a_i) at the
//     constrained vertices a_i,   u(0) = u₀,  u̇(0) = v₀,
//
// κ the tension (membrane) or Young's modulus E (bar, where Δ is d²/dx²).  The weak
// form gives A = κ ∫∇φ_i·∇φ_j and L = ∫ f φ_i (fe/assembly.hpp); the inertia is the
// chosen pair's M = ρ Bᵀ C⁻¹ B or a classical mass model (mass/mass_model.hpp).
#pragma once

#include <string>
#include <vector>

#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

struct ScalarWaveData {
  MassSpec mass;                   // the pair W^h/H^h (P1+/P0 by default) or a classical mass on W^h
  double rho = 1.0;                // density
  double kappa = 1.0;              // tension or Young's modulus
  Field f;                         // load f(x, y, t)
  bool load_is_constant = true;    // f does not depend on t
  std::vector<int> dirichlet_parts;
  Field dirichlet_value;           // g_D(x, y), constant in time
  bool obstacle = true;            // false: the same problem with no constraint
  bool obstacle_on_all_vertices = true;   // the membrane's volume obstacle
  std::vector<int> obstacle_parts;        // otherwise: the vertices of these parts (Γ_C)
  Field obstacle_g;                // lower bound u ≥ g(x, t)
  bool obstacle_moves = false;     // g depends on t: the bounds K̄^h(t) are updated every step
};

ConstrainedProblem build_scalar_wave(const Mesh& mesh, const ScalarWaveData& data);

}  // namespace cdyn
