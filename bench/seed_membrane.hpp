// seed_membrane.hpp — the problem the step benchmarks time: the seed's membrane of
// data/scenes/membrane.toml (P1+/P0, f = −0.6, u = 0.02 on the boundary and at t = 0,
// v = 0, u ≥ 0 at every free vertex), on unit_square_mesh(n), with or without its
// obstacle (the linear reference: the same S, no bounds), with another pair if asked
// (method.pair, e.g. "P1/P1").
#pragma once

#include <string>

#include "cdyn/problems/scalar_wave.hpp"
#include "cdyn/schemes/time_scheme.hpp"

namespace cdyn::bench {

struct SeedMembrane {
  Mesh mesh;
  ConstrainedProblem p;

  SeedMembrane(int n, bool obstacle, const std::string& pair = "P1+/P0") : mesh(unit_square_mesh(n)) {
    ScalarWaveData d;
    d.mass = cdyn::MassSpec::parse(pair);
    d.f = [](double, double, double) { return -0.6; };
    d.dirichlet_parts = {mesh.part_index("bottom"), mesh.part_index("right"), mesh.part_index("top"),
                         mesh.part_index("left")};
    d.dirichlet_value = [](double, double, double) { return 0.02; };
    d.obstacle = obstacle;
    d.obstacle_g = [](double, double, double) { return 0.0; };
    p = build_scalar_wave(mesh, d);
  }

  // U⁰ = 0.02, V⁰ = 0.
  State initial() const {
    State s;
    s.U = p.unknowns(p.W->interpolate([](double, double, double) { return 0.02; }));
    s.V = initial_velocity(p, Eigen::VectorXd::Zero(p.n_free()));
    return s;
  }
};

}  // namespace cdyn::bench
