// test_schemes.cpp — energy identities of the implicit schemes (docs/schemes.md).
//
//  - midpoint, no constraint: J^{n+1} = Jⁿ exactly, so |J − J0|/J0 stays at round-off.
//    The bound 1e-12 over 1000 steps sits above the round-off growth
//    measured here (1e-13 … 5e-13 for the seven models on the 4 × 4 mesh) and within
//    the independent measurement in docs/schemes.md, midpoint (≈1e-13 over 80 steps,
//    1e-11 over 800).
//  - midpoint with contact: J^{n+1} − Jⁿ = (U^{n+1} − Uⁿ)ᵀ Gᵀλ, the work of the
//    contact force, to round-off of the QP solution (tol 1e-13 relative).
//  - backward Euler, with or without contact: J never increases (up to round-off).
// Every pair of the seed and the classical mass models are checked.
#include <gtest/gtest.h>

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/problems/scalar_wave.hpp"
#include "cdyn/schemes/time_scheme.hpp"
#include "scheme_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::testing;

TEST(Schemes, MidpointConservesEnergyWithoutContact) {
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods) {
    const ConstrainedProblem p = membrane(mesh, m, false);
    auto solver = make_step_solver("pdas", tight());
    auto scheme = make_time_scheme("midpoint", p, *solver, 0.01);
    State s = initial_state(p);
    scheme->initialize(s);  // U⁰'s massless part from (14), where the pair has one
    const double J0 = scheme->energy(s).total();
    const double drift = max_energy_drift(*scheme, s, 1000, J0, std::abs(J0));
    EXPECT_LE(drift, 1e-12) << label(m);
    std::printf("midpoint, no contact, %s: max |J - J0|/J0 over 1000 steps = %.2e\n", label(m).c_str(), drift);
  }
}

TEST(Schemes, MidpointEnergyChangeIsTheContactWork) {
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods) {
    for (const char* name : {"midpoint", "midpoint_end"}) {
      const ConstrainedProblem p = membrane(mesh, m, true);
      auto solver = make_step_solver("pdas", tight());
      auto scheme = make_time_scheme(name, p, *solver, 0.01, plain());  // the identity of U^{n+1} as computed
      State s = initial_state(p);
      double J = scheme->energy(s).total(), worst = 0.0;
      int active_steps = 0;
      for (int n = 0; n < 150; ++n) {
        const Eigen::VectorXd U0 = s.U;
        const StepStats st = scheme->step(s);
        const double J1 = scheme->energy(s).total();
        const double work = (s.U - U0).dot(s.reaction);
        worst = std::max(worst, std::abs((J1 - J) - work) / std::abs(J));
        active_steps += st.active > 0;
        J = J1;
      }
      EXPECT_GT(active_steps, 10) << label(m) << ": the membrane never touched the obstacle";
      EXPECT_LE(worst, 1e-11) << label(m) << " " << name;
    }
  }
}

TEST(Schemes, BackwardEulerNeverIncreasesEnergy) {
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods)
    for (bool obstacle : {false, true}) {
      const ConstrainedProblem p = membrane(mesh, m, obstacle);
      auto solver = make_step_solver("pdas", tight());
      auto scheme = make_time_scheme("backward_euler", p, *solver, 0.01);
      State s = initial_state(p);
      expect_dissipative(*scheme, s, 200, label(m) + (obstacle ? " with contact" : ""));
    }
}

TEST(Schemes, RejectsBadInput) {
  const Mesh mesh = unit_square_mesh(2);
  const ConstrainedProblem p = membrane(mesh, kMethods[2], true);
  auto solver = make_step_solver("pdas");
  EXPECT_THROW(make_time_scheme("leapfrog", p, *solver, 0.01), InputError);
  EXPECT_THROW(make_time_scheme("midpoint", p, *solver, 0.0), InputError);
  EXPECT_THROW(make_time_scheme("midpoint", p, *solver, -1.0), InputError);
}
