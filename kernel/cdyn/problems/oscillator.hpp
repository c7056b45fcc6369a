// problems/oscillator.hpp — the seed's one-dof system (slide "Illustration of the non-uniqueness"):
//
//     m ü + k u = F(t) + λ,   u ≥ g,   λ ≥ 0,   λ (u − g) = 0,
//
// whose solution after the mass reaches the obstacle is not unique (u = a|cos ωt| for
// every a ≥ 0 when F = 0, g = 0, u(0) = 1, u̇(0) = 0): the constrained dof carries
// inertia.  It is built as the smallest member of the bar family (problems/scalar_wave.hpp), so
// that every scheme, solver and output serves it unchanged: one P1 element on [0, 1],
// clamped at x = 1, with the lumped mass; its free dof (x = 0) has mass ρh/2 = m,
// stiffness E/h = k and load ∫ f φ = f/2 = F.
#pragma once

#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/fe/fe_space.hpp"
#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

struct OscillatorData {
  double m = 1.0, k = 1.0;
  Field F = [](double, double, double) { return 0.0; };  // F(t) (x = y = 0)
  bool load_is_constant = true;
  bool obstacle = true;
  double g = 0.0;
};

// The one-element mesh the oscillator lives on (its dof is the vertex x = 0).
Mesh oscillator_mesh();

// The ConstrainedProblem of m ü + k u = F(t) + λ, u ≥ g (the seed's one-dof system, as
// eq. 16 with M = m, A = k, G = −1, α = −g), ready for any time scheme.
// InputError for m ≤ 0 or k < 0 (k = 0 is free flight, allowed).
ConstrainedProblem build_oscillator(const Mesh& mesh, const OscillatorData& data);

}  // namespace cdyn
