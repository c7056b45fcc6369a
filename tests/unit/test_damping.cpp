// test_damping.cpp — Rayleigh damping D = αM + βA in the one-step schemes
// (schemes/damping.hpp; derivations in docs/schemes.md, "Rayleigh damping").
//
//  - the one-dof oscillator m ü + (αm + βk) u̇ + k u = 0 decays like exp(−ζωt),
//    ζ = α/(2ω) + βω/2: the decay rate measured over whole damped periods converges to
//    ζω, at order 2 for the midpoint rules and order 1 for backward Euler (whose own
//    numerical damping adds about ω²dt/2);
//  - the midpoint rules' balance J^{n+1} + W_d − Jⁿ = (U^{n+1} − Uⁿ)ᵀGᵀλ holds step by
//    step to round-off, with and without contact, for every pair of the seed;
//  - backward Euler never increases J + W_d; discrete_gradient conserves it through
//    impacts;
//  - newmark, paoli_schatzman and energy_conserving refuse damping, and so does every
//    scheme a negative coefficient.
#include <gtest/gtest.h>

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/problems/oscillator.hpp"
#include "scheme_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::testing;

namespace {

SchemeParameters damped(double alpha, double beta, bool reconstruct = true) {
  SchemeParameters prm;
  prm.damping = {alpha, beta};
  prm.reconstruct = reconstruct;
  return prm;
}

// The decay rate −ln(J(t0 + m T_d)/J(t0))/(2 m T_d) of the oscillator (m = 1, k = ω²,
// u(0) = 1, u̇(0) = 0) integrated with `per_period` steps per damped period
// T_d = 2π/ω_d: the exact solution has J(t + T_d) = exp(−2ζω T_d) J(t) exactly.
double measured_decay_rate(const std::string& scheme_name, double omega, double alpha, double beta, int per_period) {
  OscillatorData o;
  o.m = 1.0;
  o.k = omega * omega;
  o.obstacle = false;
  const Mesh mesh = oscillator_mesh();
  const ConstrainedProblem p = build_oscillator(mesh, o);
  const double zeta = alpha / (2 * omega) + beta * omega / 2;
  const double Td = 2 * M_PI / (omega * std::sqrt(1 - zeta * zeta));
  auto solver = make_step_solver("pdas", tight());
  auto scheme = make_time_scheme(scheme_name, p, *solver, Td / per_period, damped(alpha, beta));
  State s;
  s.U = Eigen::VectorXd::Constant(1, 1.0);
  s.V = initial_velocity(p, Eigen::VectorXd::Zero(1));
  const int periods = 3;
  for (int n = 0; n < per_period; ++n) scheme->step(s);  // from t0 = T_d: past the start
  const double J0 = scheme->energy(s).total();
  for (int n = 0; n < periods * per_period; ++n) scheme->step(s);
  return -std::log(scheme->energy(s).total() / J0) / (2 * periods * Td);
}

}  // namespace

TEST(Damping, OscillatorDecaysAtTheModalRate) {
  const double omega = 2 * M_PI;
  struct Case {
    double alpha, beta;
  };
  for (const Case& d : {Case{0.6, 0.0}, Case{0.0, 0.02}, Case{0.3, 0.01}}) {
    const double rate = (d.alpha / (2 * omega) + d.beta * omega / 2) * omega;  // ζω
    for (const char* name : {"midpoint", "midpoint_end", "backward_euler"}) {
      const bool second_order = std::string(name) != "backward_euler";
      double previous = 0.0;
      for (int per_period : {50, 100, 200, 400}) {
        const double error = std::abs(measured_decay_rate(name, omega, d.alpha, d.beta, per_period) - rate) / rate;
        std::printf("%-15s alpha = %.2f beta = %.2f, %3d steps a period: |rate - zeta omega|/(zeta omega) = %.3e\n",
                    name, d.alpha, d.beta, per_period, error);
        if (previous > 0.0) {
          // halving dt divides the error by 4 (order 2) or 2 (order 1); measured
          // 3.99–4.00 and 1.97–1.99
          const double order = std::log2(previous / error);
          EXPECT_NEAR(order, second_order ? 2.0 : 1.0, 0.1) << name << " at " << per_period << " steps a period";
        }
        previous = error;
      }
      // at 400 steps a period: measured 4.1e-5 (midpoint rules), 0.13 … 0.16 (backward Euler)
      EXPECT_LT(previous, second_order ? 1e-4 : 0.25) << name;
    }
  }
}

TEST(Damping, MidpointBalanceHoldsStepByStep) {
  // J^{n+1} + W_d − Jⁿ = (U^{n+1} − Uⁿ)ᵀ Gᵀλ on every step (docs/schemes.md); with
  // the full steps reconstructed (eq. 14) on the steps where the reconstruction changes
  // nothing, i.e. without contact.  Measured: at most 1.6e-14 J0 without contact, 1.9e-13
  // J0 with (P1/P1, whose impacts gain energy for the damping to take: W_d = 14 J0; the
  // QP solved to 1e-13); the bound 1e-12 is the midpoint's own of test_schemes.cpp.
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods)
    for (bool obstacle : {false, true})
      for (const char* name : {"midpoint", "midpoint_end"}) {
        const ConstrainedProblem p = membrane(mesh, m, obstacle);
        auto solver = make_step_solver("pdas", tight());
        auto scheme = make_time_scheme(name, p, *solver, 0.01, damped(0.8, 0.004, !obstacle));
        State s = initial_state(p);
        scheme->initialize(s);
        double J = scheme->energy(s).total(), worst = 0.0, W = 0.0;
        const double J0 = std::abs(J);
        int active_steps = 0;
        for (int n = 0; n < 150; ++n) {
          const Eigen::VectorXd U0 = s.U;
          const StepStats st = scheme->step(s);
          const double J1 = scheme->energy(s).total();
          ASSERT_GE(st.dissipated, 0.0);
          worst = std::max(worst, std::abs(J1 + st.dissipated - J - (s.U - U0).dot(s.reaction)) / J0);
          active_steps += st.active > 0;
          W += st.dissipated;
          J = J1;
        }
        std::printf("%-8s %-13s %-12s max |J1 + W_d - J - dU.Gl|/J0 = %.1e, W_d = %.2f J0, %d steps in contact\n",
                    label(m).c_str(), name, obstacle ? "contact" : "no contact", worst, W / J0, active_steps);
        EXPECT_LE(worst, 1e-12) << label(m) << " " << name << (obstacle ? " with contact" : "");
        EXPECT_GT(W, 0.05 * J0) << label(m) << ": the damping did no work";
        if (obstacle) {
          EXPECT_GT(active_steps, 5) << label(m) << ": the membrane never touched the obstacle";
        }
      }
}

TEST(Damping, BackwardEulerNeverIncreasesEnergyPlusDissipatedWork) {
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods)
    for (bool obstacle : {false, true}) {
      const ConstrainedProblem p = membrane(mesh, m, obstacle);
      auto solver = make_step_solver("pdas", tight());
      auto scheme = make_time_scheme("backward_euler", p, *solver, 0.01, damped(0.8, 0.004));
      State s = initial_state(p);
      double J = scheme->energy(s).total(), W = 0.0;
      const double J0 = std::abs(J);
      for (int n = 0; n < 200; ++n) {
        const StepStats st = scheme->step(s);
        const double J1 = scheme->energy(s).total();
        ASSERT_GE(st.dissipated, 0.0);
        // J^{n+1} + W_d − Jⁿ = −½|ΔV|²_C − ½|δU|²_A + δUᵀGᵀλ ≤ 0 (round-off: 1e-13 J0 as
        // in test_schemes.cpp)
        ASSERT_LE(J1 + st.dissipated, J + 1e-13 * J0) << label(m) << " step " << n;
        W += st.dissipated;
        J = J1;
      }
      EXPECT_GT(W, 0.05 * J0) << label(m);
    }
}

TEST(Damping, DiscreteGradientConservesEnergyPlusDissipatedWork) {
  // H^{n+1} + W_d = Hⁿ on every step, impacts included: the step's energy error is
  // below time.energy_tol (1e-12) times the size of its terms (a few J0), so at most a
  // few 1e-10 J0 over 300 steps.  Measured: max |J + W_d − J0| = 3.9e-12 J0 (P1+/P0 on
  // the membrane, 183 steps in contact, W_d = 0.65 J0).
  const Mesh mesh = unit_square_mesh(4);
  const ConstrainedProblem p = membrane(mesh, {Element::P1Bubble, "P0"}, true);
  auto solver = make_step_solver("pdas", tight());
  auto scheme = make_time_scheme("discrete_gradient", p, *solver, 0.01, damped(0.8, 0.004));
  State s = initial_state(p);
  scheme->initialize(s);
  const double J0 = scheme->energy(s).total();
  double W = 0.0, worst = 0.0;
  int active_steps = 0;
  for (int n = 0; n < 300; ++n) {
    const StepStats st = scheme->step(s);
    W += st.dissipated;
    active_steps += st.active > 0;
    worst = std::max(worst, std::abs(scheme->energy(s).total() + W - J0) / std::abs(J0));
  }
  std::printf("discrete_gradient, damped: max |J + W_d - J0|/|J0| = %.2e, W_d = %.3f J0, %d steps in contact\n",
              worst, W / std::abs(J0), active_steps);
  EXPECT_GT(active_steps, 10);
  EXPECT_GT(W, 0.1 * std::abs(J0));
  EXPECT_LE(worst, 1e-10);
}

TEST(Damping, SchemesWithoutDampingRefuseIt) {
  const Mesh mesh = unit_square_mesh(4);
  const ConstrainedProblem p = membrane(mesh, {Element::P1, "lumped"}, true);
  auto solver = make_step_solver("pdas");
  for (const char* name : {"newmark", "paoli_schatzman", "energy_conserving"}) {
    try {
      make_time_scheme(name, p, *solver, 0.01, damped(0.1, 0.0));
      ADD_FAILURE() << name << " accepted damping";
    } catch (const InputError& e) {
      EXPECT_EQ(e.parameter(), "damping") << e.what();
    }
    EXPECT_NO_THROW(make_time_scheme(name, p, *solver, 0.01, damped(0.0, 0.0))) << name;
  }
  for (const RayleighDamping& bad : {RayleighDamping{-1.0, 0.0}, RayleighDamping{0.0, NAN}}) {
    SchemeParameters prm;
    prm.damping = bad;
    EXPECT_THROW(make_time_scheme("midpoint", p, *solver, 0.01, prm), InputError);
  }
}
