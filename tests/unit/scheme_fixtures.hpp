// scheme_fixtures.hpp — the problems the scheme tests integrate: the seed's membrane
// on a coarse mesh for every pair and classical mass model, and its initial state.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "cdyn/problems/scalar_wave.hpp"
#include "cdyn/schemes/time_scheme.hpp"

namespace cdyn::testing {

struct Method {
  Element W;
  std::string velocity;
};
inline const Method kMethods[] = {{Element::P1, "P1"},       {Element::P1, "P0"},          {Element::P1Bubble, "P0"},
                                  {Element::P1Bubble, "P1"}, {Element::P2, "P1"},          {Element::P1, "consistent"},
                                  {Element::P1, "lumped"}};
// (The redistributed mass needs a contact boundary, not a volume obstacle: it is
// checked on the bar, whose contact is one end.)

inline std::string label(const Method& m) { return to_string(m.W) + "/" + m.velocity; }

// The seed's membrane with an initial velocity so that both energy parts move:
// u0 = 0.02, v0 = −0.3 sin(πx) sin(πy), f = −0.6, u ≥ 0 at the vertices.
inline ConstrainedProblem membrane(const Mesh& mesh, const Method& m, bool obstacle) {
  ScalarWaveData d;
  d.mass = cdyn::MassSpec::parse(m.velocity, m.W);
  d.f = [](double, double, double) { return -0.6; };
  d.dirichlet_parts = {0, 1, 2, 3};
  d.dirichlet_value = [](double, double, double) { return 0.02; };
  d.obstacle = obstacle;
  d.obstacle_g = [](double, double, double) { return 0.0; };
  return build_scalar_wave(mesh, d);
}

inline State initial_state(const ConstrainedProblem& p) {
  State s;
  s.U = p.bc->restrict(p.W->interpolate([](double, double, double) { return 0.02; }));
  const Eigen::VectorXd v0 = p.bc->restrict(
      p.W->interpolate([](double x, double y, double) { return -0.3 * std::sin(M_PI * x) * std::sin(M_PI * y); }));
  s.V = initial_velocity(p, v0);
  return s;
}

// max |J − J_ref| / scale over the next `steps` steps, J the scheme's own energy
// (TimeScheme::energy: the form its conservation identity is written for).
inline double max_energy_drift(TimeScheme& scheme, State& s, int steps, double J_ref, double scale) {
  double drift = 0.0;
  for (int n = 0; n < steps; ++n) {
    scheme.step(s);
    drift = std::max(drift, std::abs(scheme.energy(s).total() - J_ref) / scale);
  }
  return drift;
}

// The schemes' own algebra on the states they compute, without the full-step
// reconstruction of eq. (14) (schemes/full_step.hpp): the identities of docs/schemes.md
// written for the midpoint's U^{n+1} = 2U^{n+½} − Uⁿ.
inline SchemeParameters plain() {
  SchemeParameters prm;
  prm.reconstruct = false;
  return prm;
}

// Backward Euler's energy inequality along `steps` steps: J never increases (up to
// 1e-13 of J0, round-off) and ends below J0.
inline void expect_dissipative(TimeScheme& scheme, State& s, int steps, const std::string& what) {
  double J = scheme.energy(s).total();
  const double J0 = J;
  for (int n = 0; n < steps; ++n) {
    scheme.step(s);
    const double J1 = scheme.energy(s).total();
    ASSERT_LE(J1, J + 1e-13 * std::abs(J0)) << what << " step " << n;
    J = J1;
  }
  EXPECT_LT(J, J0) << what << ": backward Euler is dissipative";
}

inline QPOptions tight() {
  QPOptions o;
  o.tol = 1e-13;
  return o;
}

}  // namespace cdyn::testing
