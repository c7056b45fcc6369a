// test_moving_obstacle.cpp — obstacles that move: the bounds K̄^h(t) at the time level
// each scheme constrains (problems/constrained_problem.hpp, moving_bounds).
//
// A free bar (E = ρ = 1, L = 1, c = 1) at rest, touched at x = 0 by an obstacle that
// rises at constant speed w: u(0, t) ≥ w t.  The exact solution (d'Alembert): the end
// moves with the obstacle, a compression wave of speed w runs into the bar, reflects at
// the free end as a tension wave and comes back at t = 2L/c, when the end's velocity
// would become 2w: the bar leaves the obstacle.  So the contact force is ρ c w for
// 0 < t < 2L/c and 0 after, its impulse 2ρLw, and the bar's momentum at the end
// P = 2ρLw (it leaves with mean velocity 2w, all its energy 2ρLw² the obstacle's work).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../stability/stability_fixtures.hpp"
#include "cdyn/post/linear_momentum.hpp"

using namespace cdyn;
using namespace cdyn::stability;

namespace {

constexpr double kW = 0.1;

ConstrainedProblem pushed_bar(const Mesh& mesh, const Method& m) {
  ScalarWaveData d;
  d.mass = MassSpec::parse(m.velocity, m.W);
  d.f = [](double, double, double) { return 0.0; };
  d.obstacle_on_all_vertices = false;
  d.obstacle_parts = {mesh.part_index("left")};
  d.obstacle_g = [](double, double, double t) { return kW * t; };
  d.obstacle_moves = true;
  return build_scalar_wave(mesh, d);
}

// What a run of the pushed bar measures.
struct Push {
  double impulse = 0, momentum = 0, late_force = 0, violation = 0;
  double energy = 0, work = 0, balance = 0;  // H(T), Σ Δ_tΨ, max |ΔH − Δ_tΨ| / H(T)
};

Push push(const std::string& scheme_name, int n) {
  const Mesh mesh = interval_mesh(n);
  const ConstrainedProblem p = pushed_bar(mesh, {Element::P1Bubble, "P0"});
  auto solver = make_step_solver("pdas", tight());
  const double dt = 0.5 / n;
  auto scheme = make_time_scheme(scheme_name, p, *solver, dt);
  State s;
  s.U = Eigen::VectorXd::Zero(p.n_free());
  s.V = initial_velocity(p, Eigen::VectorXd::Zero(p.n_free()));
  scheme->initialize(s);
  const int contact = p.constrained[0];
  Push r;
  std::vector<double> defects;
  for (int k = 0; k < static_cast<int>(std::lround(3.0 / dt)); ++k) {
    const double H0 = scheme->energy(s).total();
    const StepStats st = scheme->step(s);
    r.impulse += s.reaction[contact] * dt;
    if (s.t > 2.2) r.late_force = std::max(r.late_force, std::abs(s.reaction[contact]));
    r.violation = std::max(r.violation, p.max_violation(s.U, s.t));
    r.work += st.external_work.value_or(0.0);
    defects.push_back(std::abs(scheme->energy(s).total() - H0 - st.external_work.value_or(0.0)));
  }
  r.momentum = LinearMomentum(p)(s.V).x;
  r.energy = scheme->energy(s).total();
  for (double d : defects) r.balance = std::max(r.balance, d / r.energy);
  std::printf("pushed bar, %s, n = %d: impulse %.5f (exact %.5f), momentum %.5f, force after release %.1e, "
              "violation %.1e, H(T) %.6f, data's work %.6f (exact %.6f), balance %.1e\n",
              scheme_name.c_str(), n, r.impulse, 2 * kW, r.momentum, r.late_force, r.violation, r.energy, r.work,
              2 * kW * kW, r.balance);
  return r;
}

}  // namespace

// The contact force ρcw for 2L/c and nothing after: every scheme takes the impulse it
// reports as its change of momentum (midpoint and backward Euler: an identity of the
// step), keeps the end on the moving obstacle at the full steps, and lets go after 2L/c.
TEST(MovingObstacle, PushedBarTakesTheObstaclesImpulse) {
  for (const std::string scheme_name : {"midpoint", "discrete_gradient"}) {
    const Push r = push(scheme_name, 80);
    // 2ρLw within 1 % at n = 80 (measured 0.56 %: the release is resolved to dt)
    EXPECT_NEAR(r.impulse, 2 * kW, 0.01 * 2 * kW);
    // momentum = impulse: midpoint to the round-off of 480 steps (measured 8e-12);
    // discrete_gradient's correction β M ΔU at the release steps is a force of its own,
    // not in the reaction (measured 6.0e-7)
    EXPECT_NEAR(r.momentum, r.impulse, scheme_name == "midpoint" ? 1e-10 : 1e-5);
    EXPECT_LE(r.late_force, 1e-9);  // released after 2L/c
    EXPECT_LE(r.violation, 1e-12);  // never below the moving obstacle at the full steps
  }
}

// Backward Euler: the same impulse in the limit, at the rate of its numerical
// diffusion: BE damps the wave like a viscosity c²dt/2, which spreads the returning
// front over √(c² dt t), so the impulse it misses at the release is O(dt^½).
TEST(MovingObstacle, BackwardEulerImpulseConvergesAtHalfOrder) {
  std::vector<Push> runs;
  for (int n : {80, 160, 320}) runs.push_back(push("backward_euler", n));
  for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
    EXPECT_NEAR(runs[k].momentum, runs[k].impulse, 1e-10);
    EXPECT_LE(runs[k].violation, 1e-12);
    const double rate = std::log2(std::abs(runs[k].impulse - 2 * kW) / std::abs(runs[k + 1].impulse - 2 * kW));
    std::printf("backward Euler impulse: rate %.2f\n", rate);
    EXPECT_NEAR(rate, 0.5, 0.1);
  }
}

// discrete_gradient with data in t: H^{n+1} − Hⁿ = Δ_tΨ, the discrete work of the
// obstacle, at every step (to round-off), and the bar leaves with the obstacle's work
// 2ρLw² (the energy of the exact solution after 2L/c).
TEST(MovingObstacle, DiscreteGradientBalancesTheObstaclesWork) {
  const Push r = push("discrete_gradient", 80);
  EXPECT_LE(r.balance, 1e-11);                     // measured 1.3e-12
  EXPECT_NEAR(r.energy, r.work, 1e-9 * r.energy);  // H(0) = 0; the sum's round-off: measured 7.5e-11
  EXPECT_NEAR(r.work, 2 * kW * kW, 0.01 * 2 * kW * kW);
}

// discrete_gradient with a load in t, f = x sin(2πt) on the bar with the obstacle at
// rest (u(0) ≥ −0.05), up to T = 0.8: its H(T) − H(0) is the sum of its
// Δ_tΨ, and that sum converges at second order to the load's work −∫ L'(t)·U dt,
// taken from a midpoint run at dt/32 (the same quadrature, converged to 1e-7).
TEST(MovingObstacle, DiscreteGradientBalancesTheLoadsWork) {
  const Mesh mesh = interval_mesh(20);
  ScalarWaveData d;
  d.mass = MassSpec::parse("P0", Element::P1Bubble);
  d.f = [](double x, double, double t) { return x * std::sin(2 * M_PI * t); };
  d.load_is_constant = false;
  d.obstacle_on_all_vertices = false;
  d.obstacle_parts = {mesh.part_index("left")};
  d.obstacle_g = [](double, double, double) { return -0.05; };
  const ConstrainedProblem p = build_scalar_wave(mesh, d);
  auto work_of = [&](const std::string& scheme_name, double dt, double* balance) {
    auto solver = make_step_solver("pdas", tight());
    auto scheme = make_time_scheme(scheme_name, p, *solver, dt);
    State s;
    s.U = Eigen::VectorXd::Zero(p.n_free());
    s.V = initial_velocity(p, Eigen::VectorXd::Zero(p.n_free()));
    scheme->initialize(s);
    double work = 0.0, worst = 0.0;
    for (int k = 0; k < static_cast<int>(std::lround(0.8 / dt)); ++k) {
      const double H0 = scheme->energy(s).total(), t0 = s.t;
      const Eigen::VectorXd U0 = p.full(s.U);
      const StepStats st = scheme->step(s);
      if (balance) {
        work += st.external_work.value_or(0.0);
        worst = std::max(worst, std::abs(scheme->energy(s).total() - H0 - st.external_work.value_or(0.0)));
      } else {  // −ΔL·U^{n+½}, U^{n+½} the mean of the full steps (midpoint)
        const Eigen::VectorXd L1 = p.full_load(s.t);  // (full_load returns a one-time cache)
        work -= (L1 - p.full_load(t0)).dot(0.5 * (U0 + p.full(s.U)));
      }
    }
    if (balance) *balance = worst / std::abs(work);
    return work;
  };
  const double reference = work_of("midpoint", 0.1 / 32, nullptr);
  double balance = 0.0;
  const double coarse = work_of("discrete_gradient", 0.1, &balance);
  EXPECT_LE(balance, 1e-11);
  const double fine = work_of("discrete_gradient", 0.05, &balance);
  EXPECT_LE(balance, 1e-11);
  const double rate = std::log2(std::abs(coarse - reference) / std::abs(fine - reference));
  std::printf("load's work: reference %.8f, discrete_gradient %.8f (dt 0.1), %.8f (dt 0.05): rate %.2f, balance %.1e\n",
              reference, coarse, fine, rate, balance);
  EXPECT_GT(rate, 1.8);
}
