// test_schemes_impact.cpp — Newmark, Paoli–Schatzman and the energy-conserving scheme
// (docs/schemes.md), on the seed's oscillator and membrane.
//
//  - Newmark β = ¼, γ = ½ conserves J without contact (the trapezoidal rule), to the
//    same round-off bound as midpoint (1e-11 over 1000 steps; docs/schemes.md, midpoint);
//    its error on the oscillator is O(dt²), and O(dt) for γ > ½ (rates ±0.1: the
//    leading error term dominates at these dt, measured rates are 2.00 and 1.00).
//  - energy_conserving conserves E^{n+½} exactly, contact or not: after its start step
//    the energy moves by round-off only (invertible M; a singular M is refused); its interpenetration is at most one step of
//    flight, |v|·dt, at the impact.
//  - paoli_schatzman with k = 0: the velocity after a bounce is −e times the velocity
//    before it, to round-off, wherever the impact falls between two steps.
//  - the schemes constraining U^{n+1} (backward_euler, midpoint_end, newmark) keep every
//    constrained dof feasible to the QP tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cdyn/base/error.hpp"
#include "cdyn/problems/oscillator.hpp"
#include "scheme_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::testing;

namespace {

// The oscillator m = 1, k, u(0) = u0, u̇(0) = v0, obstacle u ≥ 0 (or none).
struct Oscillator {
  Mesh mesh = oscillator_mesh();
  ConstrainedProblem p;
  State s;
  Oscillator(double k, double u0, double v0, bool obstacle) {
    OscillatorData o;
    o.k = k;
    o.obstacle = obstacle;
    p = build_oscillator(mesh, o);
    s.U = Eigen::VectorXd::Constant(1, u0);
    s.V = initial_velocity(p, Eigen::VectorXd::Constant(1, v0));
  }
};

// |u(T) − cos T| for the free oscillator (k = 1, u0 = 1, v0 = 0) integrated by Newmark.
double newmark_error(double beta, double gamma, double dt) {
  Oscillator o(1.0, 1.0, 0.0, false);
  auto solver = make_step_solver("pdas", tight());
  SchemeParameters prm;
  prm.beta = beta;
  prm.gamma = gamma;
  auto scheme = make_time_scheme("newmark", o.p, *solver, dt, prm);
  const int n = static_cast<int>(std::lround(2.0 / dt));
  for (int i = 0; i < n; ++i) scheme->step(o.s);
  return std::abs(o.s.U[0] - std::cos(2.0));
}

}  // namespace

// From the first step on: J jumps once at the first step when a singular M's massless
// modes do not start in equilibrium (Bᵀ A⁰ = L − A U⁰ has no exact solution: P1+/P1,
// P2/P1 with f = −0.6, which the continuous P1 velocities cannot carry up to the
// boundary; docs/schemes.md), and is conserved from there.
TEST(Newmark, TrapezoidalRuleConservesEnergyWithoutContact) {
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods) {
    const ConstrainedProblem p = membrane(mesh, m, false);
    auto solver = make_step_solver("pdas", tight());
    auto scheme = make_time_scheme("newmark", p, *solver, 0.01);
    State s = initial_state(p);
    const double J0 = scheme->energy(s).total();
    scheme->step(s);
    const double J1 = scheme->energy(s).total();
    const double drift = max_energy_drift(*scheme, s, 999, J1, std::abs(J0));
    EXPECT_LE(drift, 1e-11) << label(m);
    std::printf("newmark (1/4, 1/2), no contact, %s: first step |J1 - J0|/J0 = %.2e, then max drift over 1000 steps = %.2e\n",
                label(m).c_str(), std::abs(J1 - J0) / std::abs(J0), drift);
  }
}

TEST(Newmark, OrderTwoForGammaHalfAndOneAbove) {
  for (const auto& [beta, gamma, order] : {std::tuple{0.25, 0.5, 2.0}, std::tuple{0.3025, 0.6, 1.0}}) {
    const double e1 = newmark_error(beta, gamma, 0.02), e2 = newmark_error(beta, gamma, 0.01);
    const double rate = std::log2(e1 / e2);
    std::printf("newmark beta = %g gamma = %g: |u(2) - cos 2| = %.3e, %.3e (dt = 0.02, 0.01), rate %.3f\n", beta, gamma,
                e1, e2, rate);
    EXPECT_NEAR(rate, order, 0.1);
  }
}

TEST(EnergyConserving, ConservesEnergyThroughContact) {
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods) {
    const ConstrainedProblem p = membrane(mesh, m, true);
    auto solver = make_step_solver("pdas", tight());
    if (p.mass->n_velocity() < p.n_free()) {  // singular M: refused (docs/schemes.md)
      EXPECT_THROW(make_time_scheme("energy_conserving", p, *solver, 0.01), InputError) << label(m);
      continue;
    }
    auto scheme = make_time_scheme("energy_conserving", p, *solver, 0.01);
    State s = initial_state(p);
    const double J0 = scheme->energy(s).total();
    scheme->step(s);
    const double J1 = scheme->energy(s).total();
    double drift = 0.0;
    int contact_steps = 0;  // steps with a dof on or below the obstacle
    for (int n = 1; n < 150; ++n) {
      scheme->step(s);
      contact_steps += (s.U - p.lower).minCoeff() <= 0.0;
      drift = std::max(drift, std::abs(scheme->energy(s).total() - J1) / std::abs(J0));
    }
    EXPECT_GE(contact_steps, 5) << label(m) << ": the membrane never touched the obstacle";
    EXPECT_LE(drift, 1e-11) << label(m);
    std::printf("energy_conserving, contact, %s: start step moves J by %.2e, then max drift %.2e\n", label(m).c_str(),
                std::abs(J1 - J0) / std::abs(J0), drift);
  }
}

TEST(EnergyConserving, InterpenetrationIsAtMostOneStepOfFlight) {
  for (double dt : {0.01, 0.005}) {
    Oscillator o(1.0, 1.0, 0.0, true);  // reaches u = 0 at t = π/2 with speed 1
    auto solver = make_step_solver("pdas", tight());
    auto scheme = make_time_scheme("energy_conserving", o.p, *solver, dt);
    double violation = 0.0, u_max_after = 0.0;
    for (int n = 0; n < static_cast<int>(3.5 / dt); ++n) {
      scheme->step(o.s);
      violation = std::max(violation, o.p.max_violation(o.s.U));
      if (o.s.t > 3.0) u_max_after = std::max(u_max_after, o.s.U[0]);
    }
    std::printf("energy_conserving oscillator dt = %g: interpenetration %.3e, rebound height %.6f\n", dt, violation,
                u_max_after);
    EXPECT_GT(violation, 0.0);  // the velocity condition lets the dof cross first
    EXPECT_LE(violation, 1.0 * dt);
    EXPECT_NEAR(u_max_after, 1.0, 2 * dt);  // elastic bounce: a = 1 in u = a|cos t|
  }
}

TEST(PaoliSchatzman, ReboundVelocityIsMinusETimesTheImpactVelocity) {
  const double dt = 0.01;
  for (double e : {0.0, 0.3, 0.5, 1.0})
    for (double u0 : {0.05, 0.0537, 0.0551, 0.0599}) {  // impacts at several phases within a step
      Oscillator o(0.0, u0, -1.0, true);               // free flight at speed 1 towards u = 0
      auto solver = make_step_solver("pdas", tight());
      SchemeParameters prm;
      prm.restitution = e;
      auto scheme = make_time_scheme("paoli_schatzman", o.p, *solver, dt, prm);
      for (int n = 0; n < 20; ++n) scheme->step(o.s);
      EXPECT_NEAR(o.s.V[0], e * 1.0, 1e-12) << "e = " << e << ", u0 = " << u0;
    }
}

TEST(PaoliSchatzman, CentralDifferenceEnergyConservedWithoutContact) {
  const Mesh mesh = unit_square_mesh(4);
  for (const char* mass : {"consistent", "lumped"}) {
    const ConstrainedProblem p = membrane(mesh, {Element::P1, mass}, false);
    auto solver = make_step_solver("pdas", tight());
    auto scheme = make_time_scheme("paoli_schatzman", p, *solver, 0.01);
    State s = initial_state(p);
    scheme->step(s);
    const double E1 = scheme->energy(s).total();
    const double drift = max_energy_drift(*scheme, s, 999, E1, std::abs(E1));
    std::printf("paoli_schatzman, no contact, %s: max |E - E1|/E1 over 1000 steps = %.2e\n", mass, drift);
    EXPECT_LE(drift, 1e-11) << mass;
  }
}

TEST(Schemes, ConstraintAtTheEndOfTheStepHoldsToTheQPTolerance) {
  const Mesh mesh = unit_square_mesh(4);
  for (const Method& m : kMethods)
    for (const char* name : {"backward_euler", "midpoint_end", "newmark"}) {
      const ConstrainedProblem p = membrane(mesh, m, true);
      auto solver = make_step_solver("pdas", tight());
      auto scheme = make_time_scheme(name, p, *solver, 0.01);
      State s = initial_state(p);
      double violation = 0.0;
      for (int n = 0; n < 100; ++n) {
        scheme->step(s);
        violation = std::max(violation, p.max_violation(s.U));
      }
      EXPECT_LE(violation, 1e-13) << label(m) << " " << name;
    }
}

TEST(Schemes, RefuseWhatTheyCannotDo) {
  const Mesh mesh = unit_square_mesh(2);
  const ConstrainedProblem p = membrane(mesh, {Element::P1Bubble, "P0"}, true);
  auto solver = make_step_solver("pdas");
  EXPECT_THROW(make_time_scheme("paoli_schatzman", p, *solver, 0.01), InputError);  // singular M
  SchemeParameters bad;
  bad.beta = 0.0;
  EXPECT_THROW(make_time_scheme("newmark", p, *solver, 0.01, bad), InputError);
  bad = {};
  bad.gamma = 0.4;
  EXPECT_THROW(make_time_scheme("newmark", p, *solver, 0.01, bad), InputError);
  const ConstrainedProblem q = membrane(mesh, {Element::P1, "lumped"}, true);
  bad = {};
  bad.restitution = 1.5;
  EXPECT_THROW(make_time_scheme("paoli_schatzman", q, *solver, 0.01, bad), InputError);
}
