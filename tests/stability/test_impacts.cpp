// test_impacts.cpp — fast impacts, grazing contact and chattering.
//
// Fast impacts (×100 the default impact speed).
//   - The falling bar (FallingBar: L = 1, n = 20, gap d = 0.1) at v₀ = 30 instead of
//     0.3, dt = 0.01: the bar moves 3 gaps per step.  Expected: no NaN; for backward
//     Euler and midpoint_end the constrained U^{n+1} is feasible to the QP tolerance
//     (1e-13 relative to |U| ≤ 60: asserted 1e-10 absolute) and J ≤ J0; for the
//     half-step midpoint J changes by the contact work only (test_large_steps.cpp).
//   - Positive homogeneity: the discrete problem of (v₀, d) and of (100 v₀, 100 d) are
//     the same up to the factor 100 (the obstacle u ≥ −d is a cone shifted by d, the
//     equations are linear, the QP's tolerance is relative), so the fast run must be
//     exactly 100 times the default one — a check that no absolute threshold hides in
//     the solver or the schemes.  Tolerance 1e-11 relative: each step rounds to a few
//     ε and the QP stops at a KKT residual of 1e-13 relative, over 300 steps.
//   - The membrane with v₀ ×100 (−30 sin πx sin πy), n = 8, dt = 0.005, 200 steps:
//     the same expectations as the bar.
// Grazing: the oscillator (m = k = 1) starting ON the obstacle u ≥ −1 at rest,
// u(0) = −1, u̇(0) = 0: it touches with zero velocity and zero contact force at t = 0,
// 2π, 4π (the spring pulls it away), and the exact solution is the free one, −cos t.  And the membrane at rest on the obstacle with no load (U = g,
// λ = 0 at every constrained dof: every constraint degenerate).  Expected: each
// step's QP converges in a bounded number of iterations (no active-set cycling),
// asserted ≤ 5 (pdas from a warm start needs 1–3 here, measured; its limit is 100),
// and the grazing oscillator stays within O(dt²) of cos t.
// Chattering: Paoli–Schatzman with restitution e = 0.1 (repeated small bounces):
// the bouncing oscillator (k = 0, F = −1, u(0) = 1: impacts at √2, then every
// 2√2·eᵏ, accumulating at t∞ = √2(1 + 2e/(1 − e)) ≈ 1.728, then at rest) and the
// membrane with the consistent mass (f = −0.6, QP in the M-norm).  Expected: QP
// iterations bounded (≤ 5), J non-increasing after the first step, the oscillator at
// rest on the obstacle after t∞ (|u| and |v| at most one step's free flight:
// g·dt² and g·dt).
#include <gtest/gtest.h>

#include "cdyn/problems/oscillator.hpp"
#include "stability_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::stability;

namespace {

const Method kP1BubbleP0{Element::P1Bubble, "P0"};

struct FallingRun {
  RunRecord record;
  Eigen::VectorXd U;  // the final displacement
};

FallingRun falling_bar(const std::string& scheme_name, double v0, double d, const SchemeParameters& prm = {}) {
  const Mesh mesh = interval_mesh(20);
  FallingBar b;
  b.v0 = v0;
  b.d = d;
  const ConstrainedProblem p = bar(mesh, kP1BubbleP0, false, -d);
  auto solver = make_step_solver("pdas", tight());
  auto scheme = make_time_scheme(scheme_name, p, *solver, 0.01, prm);
  State s = falling_bar_state(p, b);
  FallingRun out{run(*scheme, p, s, 300), s.U};
  char what[128];
  std::snprintf(what, sizeof what, "falling bar %s v0 = %g d = %g (exact J = %g)", scheme_name.c_str(), v0, d,
                b.energy(0.0));
  print(what, out.record);
  return out;
}

constexpr int kMaxQPIterations = 5;

}  // namespace

TEST(FastImpacts, FallingBarAtHundredTimesTheSpeed) {
  for (const std::string scheme : {"backward_euler", "midpoint_end", "midpoint"}) {
    // (midpoint: its own states, U^{n+1} = 2U^{n+½} − Uⁿ, whose identity is checked)
    const RunRecord r = falling_bar(scheme, 30.0, 0.1, scheme == "midpoint" ? plain() : SchemeParameters{}).record;
    ASSERT_TRUE(r.finite) << scheme;
    if (scheme == "midpoint") {
      // its U^{n+1} = 2U^{n+½} − Uⁿ is not the constrained unknown: at the first step
      // the half step lands on the obstacle and U¹ = −2d, a violation of d (printed);
      // J changes by the contact work only (1e-12·|J0| per step: test_large_steps.cpp)
      EXPECT_LE(std::abs(r.J_end - r.J0 - r.contact_work), 1e-12 * std::abs(r.J0) * r.steps);
      continue;
    }
    EXPECT_LE(r.max_violation, 1e-10) << scheme;
    EXPECT_LE(r.growth(), 1e-12 * std::abs(r.J0)) << scheme;
  }
}

TEST(FastImpacts, HundredTimesFasterOntoAHundredTimesFartherObstacleIsTheSameRunScaled) {
  for (const std::string scheme : {"backward_euler", "midpoint_end", "midpoint", "newmark"}) {
    const FallingRun slow = falling_bar(scheme, 0.3, 0.1), fast = falling_bar(scheme, 30.0, 10.0);
    const double difference = (fast.U / 100.0 - slow.U).lpNorm<Eigen::Infinity>() / slow.U.lpNorm<Eigen::Infinity>();
    std::printf("  %s: |U_fast/100 - U_slow| / |U_slow| = %.2e\n", scheme.c_str(), difference);
    EXPECT_LE(difference, 1e-11) << scheme;
  }
}

TEST(FastImpacts, MembraneAtHundredTimesTheSpeed) {
  const Mesh mesh = unit_square_mesh(8);
  const ConstrainedProblem p = membrane(mesh, kP1BubbleP0, true);
  for (const std::string scheme_name : {"backward_euler", "midpoint_end", "midpoint"}) {
    auto solver = make_step_solver("pdas", tight());
    auto scheme = make_time_scheme(scheme_name, p, *solver, 0.005);
    State s = initial_state(p);
    s.V *= 100.0;  // v₀ = −30 sin πx sin πy
    const RunRecord r = run(*scheme, p, s, 200);
    print("membrane v0 x100 " + scheme_name, r);
    ASSERT_TRUE(r.finite) << scheme_name;
    EXPECT_LE(r.max_iterations, 10) << scheme_name;
    if (scheme_name == "midpoint") continue;
    EXPECT_LE(r.max_violation, 1e-12) << scheme_name;  // 1e-13 relative to |U| ≤ 1
    EXPECT_LE(r.growth(), 1e-12 * std::abs(r.J0)) << scheme_name;
  }
}

TEST(Grazing, OscillatorTouchingWithZeroVelocityFollowsTheFreeSolution) {
  const Mesh mesh = oscillator_mesh();
  OscillatorData o;
  o.g = -1.0;
  const ConstrainedProblem p = build_oscillator(mesh, o);
  const double dt = 0.01;
  for (const std::string scheme_name : {"backward_euler", "midpoint", "midpoint_end", "newmark"}) {
    auto solver = make_step_solver("pdas", tight());
    auto scheme = make_time_scheme(scheme_name, p, *solver, dt);
    State s;
    s.U = Eigen::VectorXd::Constant(1, -1.0);
    s.V = initial_velocity(p, Eigen::VectorXd::Zero(1));
    double error = 0.0;
    int max_iterations = 0, active_steps = 0;
    for (int n = 0; n < static_cast<int>(4 * M_PI / dt) + 2; ++n) {  // two periods: through the graze at t = 2π, 4π
      const StepStats st = scheme->step(s);
      max_iterations = std::max(max_iterations, st.qp_iterations);
      active_steps += st.active > 0;
      error = std::max(error, std::abs(s.U[0] + std::cos(s.t)));
    }
    std::printf("grazing oscillator %s: max |u + cos t| = %.3e, steps with an active constraint %d, QP iterations "
                "max %d\n", scheme_name.c_str(), error, active_steps, max_iterations);
    EXPECT_LE(max_iterations, kMaxQPIterations) << scheme_name;
    // second-order schemes: the phase error of the trapezoidal family is t·dt²/12, at
    // most 4π·dt²/12 ≈ dt² over two periods; backward Euler is first order and damps
    // (amplitude e^{−t·dt/2}): |u + cos t| ≤ 1 − e^{−2π dt} ≈ 2π dt
    EXPECT_LE(error, scheme_name == "backward_euler" ? 2 * M_PI * dt : 1.5 * dt * dt) << scheme_name;
  }
}

TEST(Grazing, MembraneRestingOnTheObstacleWithNoLoad) {
  const Mesh mesh = unit_square_mesh(8);
  for (const Method& m : kMethods) {
    ScalarWaveData d;
    d.mass = cdyn::MassSpec::parse(m.velocity, m.W);
    d.f = [](double, double, double) { return 0.0; };
    d.dirichlet_parts = {0, 1, 2, 3};
    d.dirichlet_value = [](double, double, double) { return 0.0; };
    d.obstacle_g = [](double, double, double) { return 0.0; };
    const ConstrainedProblem p = build_scalar_wave(mesh, d);
    for (const std::string scheme_name : {"backward_euler", "midpoint", "midpoint_end", "newmark"}) {
      auto solver = make_step_solver("pdas", tight());
      auto scheme = make_time_scheme(scheme_name, p, *solver, 0.01);
      State s;
      s.U = Eigen::VectorXd::Zero(p.n_free());
      s.V = Eigen::VectorXd::Zero(p.mass->n_velocity());
      const RunRecord r = run(*scheme, p, s, 50);
      EXPECT_LE(r.max_iterations, kMaxQPIterations) << label(m) << " " << scheme_name;
      EXPECT_EQ(s.U.lpNorm<Eigen::Infinity>(), 0.0) << label(m) << " " << scheme_name;  // rest is exact
      std::printf("resting membrane %s %s: QP iterations max %d, active-set changes %d\n", label(m).c_str(),
                  scheme_name.c_str(), r.max_iterations, r.active_changes);
    }
  }
}

TEST(Chattering, BouncingOscillatorWithLowRestitutionComesToRest) {
  const Mesh mesh = oscillator_mesh();
  OscillatorData o;
  o.k = 0.0;
  o.F = [](double, double, double) { return -1.0; };
  const ConstrainedProblem p = build_oscillator(mesh, o);
  const double dt = 0.01, e = 0.1;
  SchemeParameters prm;
  prm.restitution = e;
  auto solver = make_step_solver("pdas", tight());
  auto scheme = make_time_scheme("paoli_schatzman", p, *solver, dt, prm);
  State s;
  s.U = Eigen::VectorXd::Constant(1, 1.0);
  s.V = initial_velocity(p, Eigen::VectorXd::Zero(1));
  scheme->step(s);
  const RunRecord r = run(*scheme, p, s, 399);  // to t = 4 > t∞ ≈ 1.728
  print("bouncing oscillator paoli_schatzman e = 0.1", r);
  ASSERT_TRUE(r.finite);
  EXPECT_LE(r.max_iterations, kMaxQPIterations);
  // no energy gain after the start step: J = ½v² + u is rounded to ~ε per step, and
  // 400 steps of it stay below 1e-12·J0 (measured 4.3e-13)
  EXPECT_LE(r.J_max, r.J0 + 1e-12 * std::abs(r.J0));
  std::printf("  at t = %g: u = %.3e, v = %.3e\n", s.t, s.U[0], s.V[0]);
  EXPECT_LE(std::abs(s.U[0]), dt * dt);  // at rest on the obstacle, to one step of free fall
  EXPECT_LE(std::abs(s.V[0]), dt);
}

TEST(Chattering, MembraneConsistentMassPaoliSchatzmanLowRestitution) {
  const Mesh mesh = unit_square_mesh(8);
  const ConstrainedProblem p = membrane(mesh, {Element::P1, "consistent"}, true);
  SchemeParameters prm;
  prm.restitution = 0.1;
  auto solver = make_step_solver("pdas", tight());
  auto scheme = make_time_scheme("paoli_schatzman", p, *solver, 0.002, prm);
  State s = initial_state(p);
  const RunRecord r = run(*scheme, p, s, 1000);
  print("membrane P1/consistent paoli_schatzman e = 0.1", r);
  ASSERT_TRUE(r.finite);
  EXPECT_LE(r.max_iterations, kMaxQPIterations);
}
