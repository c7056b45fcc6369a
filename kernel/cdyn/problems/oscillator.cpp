// problems/oscillator.cpp — the one-dof system as a one-element bar with the lumped mass.
#include "cdyn/problems/oscillator.hpp"

#include "cdyn/base/error.hpp"
#include "cdyn/problems/scalar_wave.hpp"

namespace cdyn {

Mesh oscillator_mesh() { return interval_mesh(1, 1.0); }

ConstrainedProblem build_oscillator(const Mesh& mesh, const OscillatorData& o) {
  if (!(o.m > 0.0)) throw InputError("m", "the mass must be positive");
  if (!(o.k >= 0.0)) throw InputError("k", "the stiffness must be non-negative");
  if (mesh.dim != 1 || mesh.n_cells() != 1) throw InputError("oscillator: needs oscillator_mesh()");
  ScalarWaveData d;
  d.mass = {MassSpec::Model::Lumped, Element::P1, Element::P0};
  d.rho = 2.0 * o.m;  // lumped mass of the free vertex: ρh/2 = m
  const Field F = o.F;
  d.f = [F](const Point& p, double t) { return 2.0 * F(p, t); };  // ∫ f φ = f/2 = F
  d.load_is_constant = o.load_is_constant;
  d.dirichlet_parts = {mesh.part_index("right")};
  d.dirichlet_value = [](double, double, double) { return 0.0; };
  d.obstacle = o.obstacle;
  d.obstacle_on_all_vertices = false;
  d.obstacle_parts = {mesh.part_index("left")};
  const double g = o.g;
  d.obstacle_g = [g](double, double, double) { return g; };
  ConstrainedProblem p = build_scalar_wave(mesh, d);  // with E = 1; the stiffness E/h = k
  p.A_full *= o.k;                                     // is set here so that k = 0 is allowed
  p.A *= o.k;
  return p;
}

}  // namespace cdyn
