// test_friction.cpp — nodal friction in the time schemes (problems/friction.hpp,
// schemes/step_qp_scheme.hpp), on an elastic block resting on the plane y = 0 under a
// gravity turned by θ, g = G (sin θ, −cos θ): the block on an inclined plane, seen in the
// plane's frame.
//
//  (i)   Coulomb with μ = 0 is the frictionless run (same rotated unknowns) to round-off;
//  (ii)  Tresca with s = ∞ is the bonded run: the same block with the bottom's x
//        component held by a Dirichlet condition (a roller: an independent problem);
//  (iii) the energy balance of every step: midpoint_end J^{n+1} + W_f − Jⁿ = δU_Nᵀλ_N
//        to the step's tolerance, backward Euler J^{n+1} + W_f − Jⁿ ≤ 0;
//  (iv)  the block sticks when tan θ ≤ μ (no slip at all) and slides otherwise, its
//        momentum growing like m G (sin θ − μ cos θ) t;
//  (v)   every step solver gives the same frictional steps; friction is refused where
//        it is not implemented (schemes without it; space: test_friction_3d.cpp);
//  (vi)  the semismooth Newton method's fallback when its sets cycle, and a restart
//        from the scheme's memory.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/post/linear_momentum.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/qp/friction_solvers.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/schemes/time_scheme.hpp"
#include "trajectory_fixtures.hpp"

using namespace cdyn;
using cdyn::testing::max_abs_difference;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
constexpr double kG = 1.0;

Field constant(double c) {
  return [c](const Point&, double) { return c; };
}

// The unit block on y = 0, E = 1000, ν = 0.3, ρ = 1 (mass m = 1), gravity turned by θ.
ElasticContactData block(const Mesh& mesh, double theta, const std::string& mass = "P1/P0") {
  ElasticContactData d;
  d.mass = MassSpec::parse(mass);
  const Lame l = lame_parameters(1000.0, 0.3);
  d.lambda = l.lambda;
  d.mu = l.mu;
  d.gravity = {kG * std::sin(theta), -kG * std::cos(theta), 0.0};
  d.contact_parts = {mesh.part_index("bottom")};
  d.obstacle_point = {0.0, 0.0};
  d.obstacle_normal = {0.0, 1.0};
  return d;
}

ElasticContactData with_friction(ElasticContactData d, FrictionLaw law, double value) {
  d.obstacles = obstacles_of(d);
  d.obstacles[0].friction.law = law;
  if (law == FrictionLaw::Coulomb) d.obstacles[0].friction.mu = constant(value);
  if (law == FrictionLaw::Tresca) d.obstacles[0].friction.threshold = constant(value);
  return d;
}

struct Step {
  double t = 0.0, J = 0.0, friction_work = 0.0, normal_work = 0.0, contact_work = 0.0;
  Point momentum;
  Eigen::VectorXd U_full;
  std::vector<int> status;
  Eigen::VectorXd slip;
};

// Runs n steps from rest (U⁰ = 0, V⁰ = 0, or the given initial velocity rate).
std::vector<Step> run(const ConstrainedProblem& p, const std::string& scheme_name, const std::string& solver_name,
                      double dt, int n, const Eigen::VectorXd& Udot0 = {}) {
  QPOptions o;
  o.tol = 1e-13;
  auto solver = make_step_solver(solver_name, o);
  SchemeParameters parameters;
  parameters.tol = 1e-12;
  auto scheme = make_time_scheme(scheme_name, p, *solver, dt, parameters);
  State s;
  s.U = Eigen::VectorXd::Zero(p.n_free());
  s.V = initial_velocity(p, Udot0.size() ? Udot0 : Eigen::VectorXd::Zero(p.n_free()));
  scheme->initialize(s);
  const LinearMomentum momentum(p);
  std::vector<Step> out;
  out.push_back({0.0, scheme->energy(s).total(), 0.0, 0.0, 0.0, momentum(s.V), p.full(s.U), {}, {}});
  for (int k = 0; k < n; ++k) {
    const Eigen::VectorXd U0 = s.U;
    const StepStats stats = scheme->step(s);
    Step st{s.t, scheme->energy(s).total(), stats.friction_work, 0.0, 0.0, momentum(s.V), p.full(s.U), s.contact_status,
            s.slip};
    const Eigen::VectorXd dU = s.U - U0;
    st.contact_work = dU.dot(s.reaction);
    for (int i : p.constrained) st.normal_work += dU[i] * s.reaction[i];
    out.push_back(st);
  }
  return out;
}

// An initial velocity (1, −1/2) (sliding into the plane), a translation of the block.
Eigen::VectorXd thrown(const ConstrainedProblem& p) {
  const Eigen::VectorXd v = p.W->interpolate(std::vector<Field>{constant(1.0), constant(-0.5)});
  return p.unknowns(v);
}

}  // namespace

// (i) μ = 0: every step's QP is the frictionless one (the slip sets carry no force).
TEST(Friction, CoulombWithZeroMuIsFrictionless) {
  const Mesh mesh = unit_square_mesh(4);
  for (const std::string scheme : {"backward_euler", "midpoint_end"}) {
    ElasticContactData d = block(mesh, 0.3);
    d.rotate_always = true;  // the same unknowns as with friction
    const ConstrainedProblem plain = build_elastic_contact(mesh, d);
    const ConstrainedProblem frictional = build_elastic_contact(mesh, with_friction(block(mesh, 0.3), FrictionLaw::Coulomb, 0.0));
    ASSERT_EQ(frictional.friction.size(), 5u);
    const auto a = run(plain, scheme, "pdas", 0.01, 60, thrown(plain));
    const auto b = run(frictional, scheme, "pdas", 0.01, 60, thrown(frictional));
    // the same QPs, solved by other paths (the semismooth Newton's sets, then pdas
    // warm-started from them), each to the step's tolerance (1e-13 on the QP, 1e-12 on
    // the friction residual): measured 1.1e-13 (backward Euler), with |U| ≈ 0.6
    std::printf("mu = 0, %s: max |U - U_frictionless| = %.2e\n", scheme.c_str(), max_abs_difference(a, b));
    EXPECT_LE(max_abs_difference(a, b), 1e-12) << scheme;
    for (const Step& st : b) EXPECT_EQ(st.friction_work, 0.0);
  }
}

// (ii) s = ∞: the bottom vertices never move along the plane; the same as holding
// their x component by a Dirichlet condition.
TEST(Friction, TrescaWithInfiniteThresholdIsBonded) {
  const Mesh mesh = unit_square_mesh(4);
  for (const std::string scheme : {"backward_euler", "midpoint_end"}) {
    ElasticContactData roller = block(mesh, 0.3);
    roller.dirichlet_parts = {mesh.part_index("bottom")};
    roller.dirichlet_components = {0};
    const ConstrainedProblem bonded = build_elastic_contact(mesh, roller);
    const ConstrainedProblem frictional = build_elastic_contact(mesh, with_friction(block(mesh, 0.3), FrictionLaw::Tresca, kInf));
    const auto a = run(bonded, scheme, "pdas", 0.01, 60);
    const auto b = run(frictional, scheme, "pdas", 0.01, 60);
    std::printf("s = inf, %s: max |U - U_bonded| = %.2e (max |U| = %.2e)\n", scheme.c_str(), max_abs_difference(a, b),
                b.back().U_full.lpNorm<Eigen::Infinity>());
    EXPECT_LE(max_abs_difference(a, b), 1e-14) << scheme;
    for (std::size_t k = 1; k < b.size(); ++k)
      for (int i = 0; i < b[k].slip.size(); ++i) EXPECT_EQ(b[k].slip[i], 0.0);
  }
}

// (iii) The energy balance, every step, for the thrown block (impact, then sliding).
TEST(Friction, EnergyBalancePerStep) {
  const Mesh mesh = unit_square_mesh(4);
  for (const auto& [law, value] : {std::pair{FrictionLaw::Coulomb, 0.3}, std::pair{FrictionLaw::Tresca, 0.05}}) {
    const ConstrainedProblem p = build_elastic_contact(mesh, with_friction(block(mesh, 0.3), law, value));
    const auto mid = run(p, "midpoint_end", "pdas", 0.01, 100, thrown(p));
    double identity = 0.0, law_error = 0.0, balance = 0.0, total_work = 0.0, scale = 0.0;
    for (std::size_t k = 1; k < mid.size(); ++k) {
      const Step &a = mid[k - 1], &b = mid[k];
      // J^{n+1} − Jⁿ = δUᵀλ: an identity of the scheme (round-off) ...
      identity = std::max(identity, std::abs(b.J - a.J - b.contact_work));
      // ... and δU_Tᵀλ_T = −W_f at the solution of the step (to its tolerance)
      law_error = std::max(law_error, std::abs(b.contact_work - b.normal_work + b.friction_work));
      balance = std::max(balance, std::abs(b.J + b.friction_work - a.J - b.normal_work));
      total_work += b.friction_work;
      scale = std::max(scale, std::abs(b.J));
    }
    std::printf("%s: max |J^{n+1} - J^n - dU.lambda| = %.2e, max |W_f + dU_T.lambda_T| = %.2e, "
                "max |J^{n+1} + W_f - J^n - dU_N.lambda_N| = %.2e; max |J| = %.2e, sum W_f = %.3e\n",
                to_string(law).c_str(), identity, law_error, balance, scale, total_work);
    EXPECT_GT(total_work, 0.05 * scale) << to_string(law);  // friction does work
    // round-off of J's terms (docs/elasticity.md §5: 1e-11 for these identities)
    EXPECT_LE(identity, 1e-11 * scale) << to_string(law);
    // W_f = s|δU_T| against −δU_Tᵀλ_T: each step's friction residual is ≤ 1e-12 of
    // |X| (≈ 1), i.e. the slip and the force are each right to about 1e-12 relative,
    // and W_f ≤ 0.35 J over the run; measured 2.7e-12 (Coulomb), 6.5e-14 (Tresca),
    // and the balance 3.4e-12, 1.0e-12 (identity 7.6e-13, 1.1e-12)
    EXPECT_LE(law_error, 1e-10 * scale) << to_string(law);
    EXPECT_LE(balance, 1e-10 * scale) << to_string(law);

    const auto be = run(p, "backward_euler", "pdas", 0.01, 100, thrown(p));
    for (std::size_t k = 1; k < be.size(); ++k)
      EXPECT_LE(be[k].J + be[k].friction_work - be[k - 1].J, 1e-12 * scale) << to_string(law) << " step " << k;
  }
}

// (iv) The inclined plane, with a flat plate 2 × ½ (the tilting moment of the weight
// varies the pressure along the base by ±3 tan θ h/L = ±27 % at θ = 20°; a square block
// would lift its uphill corner and slip locally where the pressure vanishes — measured,
// a physical effect of the elastic body, not the law).  Sticks for tan θ ≤ μ, slides
// with a = G (sin θ − μ cos θ) otherwise.
TEST(Friction, BlockOnAnInclinedPlane) {
  Mesh mesh = unit_square_mesh(8);
  for (Point& v : mesh.vertices) v = {2.0 * v.x, 0.5 * v.y};
  const double m = 1.0;  // ρ |Ω|
  {  // tan 20° = 0.36 < μ = 0.7: sticks, not a single vertex slips
    const double theta = 20.0 * M_PI / 180.0;
    const ConstrainedProblem p = build_elastic_contact(mesh, with_friction(block(mesh, theta), FrictionLaw::Coulomb, 0.7));
    const auto st = run(p, "backward_euler", "pdas", 0.01, 100);
    int slips = 0;
    for (std::size_t k = 1; k < st.size(); ++k) {
      for (int i = 0; i < st[k].slip.size(); ++i) slips += st[k].slip[i] != 0.0;
      for (std::size_t i = 0; i < st[k].status.size(); ++i) EXPECT_EQ(st[k].status[i], 1) << "step " << k;
    }
    EXPECT_EQ(slips, 0);
  }
  {  // tan 40° = 0.84 > μ = 0.5: slides
    const double theta = 40.0 * M_PI / 180.0, mu = 0.5;
    const ConstrainedProblem p = build_elastic_contact(mesh, with_friction(block(mesh, theta), FrictionLaw::Coulomb, mu));
    const auto st = run(p, "backward_euler", "pdas", 0.01, 100);
    const double a = kG * (std::sin(theta) - mu * std::cos(theta));
    double worst = 0.0;
    for (std::size_t k = 20; k < st.size(); ++k) worst = std::max(worst, std::abs(st[k].momentum.x - m * a * st[k].t));
    std::printf("sliding: max |P_x - m a t| over t in [0.2, 1] = %.3e (m a = %.4f)\n", worst, m * a);
    // the transient of the first steps (the block settles on the plane, its normal
    // momentum feeds μ ΣN − μ m G cos θ) leaves P_x − m a t = μ m v_y: measured 1.4e-4 m a
    EXPECT_LE(worst, 1e-3 * m * a);
    for (int status : st.back().status) EXPECT_EQ(status, 2);
  }
}

// (v) Every step solver, the same frictional run.
TEST(Friction, SolversAgree) {
  const Mesh mesh = unit_square_mesh(4);
  const ConstrainedProblem p = build_elastic_contact(mesh, with_friction(block(mesh, 0.3), FrictionLaw::Coulomb, 0.3));
  const auto ref = run(p, "backward_euler", "pdas", 0.01, 40, thrown(p));
  for (const std::string& name : step_solver_names()) {
    const auto other = run(p, "backward_euler", name, 0.01, 40, thrown(p));
    // each step to friction_residual ≤ 1e-12 (|U| ≈ 0.6): measured ≤ 1.7e-11 (pgs, whose
    // inner residual is checked every 10 sweeps), 1.1e-14 (ipopt, nlopt)
    std::printf("%s against pdas: max |dU| = %.2e\n", name.c_str(), max_abs_difference(ref, other));
    EXPECT_LE(max_abs_difference(ref, other), 1e-10) << name;
  }
}

TEST(Friction, RefusedWhereNotImplemented) {
  const Mesh mesh = unit_square_mesh(4);
  const ConstrainedProblem p = build_elastic_contact(mesh, with_friction(block(mesh, 0.3), FrictionLaw::Coulomb, 0.3));
  auto solver = make_step_solver("pdas");
  for (const std::string name : {"midpoint", "newmark", "discrete_gradient", "energy_conserving", "paoli_schatzman"})
    EXPECT_THROW(make_time_scheme(name, p, *solver, 0.01), InputError) << name;
  const ConstrainedProblem bubble =
      build_elastic_contact(mesh, with_friction(block(mesh, 0.3, "P1+/P0"), FrictionLaw::Coulomb, 0.3));
  EXPECT_THROW(make_time_scheme("midpoint_end", bubble, *solver, 0.01), InputError);
  EXPECT_EQ(recommended_scheme(bubble), "backward_euler");
  EXPECT_NO_THROW(make_time_scheme("backward_euler", bubble, *solver, 0.01));

  try {
    build_elastic_contact(mesh, with_friction(block(mesh, 0.3), FrictionLaw::Coulomb, -0.1));
    FAIL() << "a negative mu accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.parameter(), "friction_mu");
  }
}

// The semismooth Newton method converges only locally: started from the frictionless
// sets (every node slipping, s = 0) on the first step of data/scenes/incline_block.toml
// at θ = 15°, μ = 0.3, its sets cycle for the Tresca problem of the first thresholds
// (measured without the fallback: no convergence in 50 iterations, residual 4e-3).  It
// must notice, solve that Tresca problem by projected Gauss–Seidel, and go on to the
// solution projected Gauss–Seidel finds alone.
TEST(Friction, CyclingSetsFallBackToProjectedGaussSeidel) {
  const Mesh mesh = read_mesh(std::string(CDYN_SOURCE_DIR) + "/data/geo/plate.geo");
  ElasticContactData d;
  d.mass = MassSpec::parse("P1/P0");
  const Lame l = lame_parameters(1e8, 0.3);
  d.lambda = l.lambda;
  d.mu = l.mu;
  d.rho = 1000.0;
  const double theta = 15.0 * M_PI / 180.0;
  d.gravity = {9.81 * std::sin(theta), -9.81 * std::cos(theta), 0.0};
  d.contact_parts = {mesh.part_index("bottom")};
  const ConstrainedProblem p = build_elastic_contact(mesh, with_friction(d, FrictionLaw::Coulomb, 0.3));
  const double dt = 1e-3;
  BoundQP qp;  // backward Euler's first step from rest: S = M/dt² + A, r = L
  qp.S = p.A + (1.0 / (dt * dt)) * *p.mass->matrix();
  qp.S.makeCompressed();
  qp.r = p.load(dt);
  qp.lower = p.lower;
  qp.upper = p.upper;
  FrictionConditions f;
  f.reference = Eigen::VectorXd::Zero(p.n_free());
  for (const FrictionNode& node : p.friction) f.contacts.push_back({node.normal, node.tangential, true, node.mu, 0.0});
  FrictionResult frictionless;  // the warm start: every node slipping freely
  frictionless.qp.X = f.reference;
  frictionless.threshold = Eigen::VectorXd::Zero(f.contacts.size());
  frictionless.stick.assign(f.contacts.size(), 0);
  frictionless.direction = Eigen::VectorXd::Zero(p.n_free());
  FrictionOptions o;
  o.tol = 1e-12;
  QPOptions qo;
  qo.tol = 1e-13;
  auto inner = make_step_solver("pdas", qo);
  const FrictionResult ssn = solve_friction_ssn(qp, f, *inner, o, &frictionless);
  const FrictionResult pgs = solve_friction_pgs(qp, f, o);
  const double scale = pgs.qp.X.lpNorm<Eigen::Infinity>();
  std::printf("fallbacks %d, inner iterations %d, |X_ssn - X_pgs| = %.2e of |X| = %.2e (|D^-1 r| = %.2e)\n",
              ssn.fallbacks, ssn.qp.iterations, (ssn.qp.X - pgs.qp.X).lpNorm<Eigen::Infinity>(), scale,
              qp.r.cwiseQuotient(scaling_diagonal(qp)).lpNorm<Eigen::Infinity>());
  EXPECT_GE(ssn.fallbacks, 1);
  EXPECT_TRUE(ssn.converged);
  // both to friction_residual ≤ 1e-12 |X| (|X| > |D⁻¹r| here), an error in X up to that times the
  // conditioning of D^-½ S D^-½ (docs/qp.md §2): measured 1.7e-10 |X|
  EXPECT_LE((ssn.qp.X - pgs.qp.X).lpNorm<Eigen::Infinity>(), 1e-9 * scale);
}

// A frictional run goes on from its memory (the sets, thresholds and slip directions of
// the last step, schemes/scheme_memory.hpp) as if never stopped: what `cdyn run
// --resume` relies on.
TEST(Friction, RestoredSchemeRepeatsTheRun) {
  const Mesh mesh = unit_square_mesh(4);
  const ConstrainedProblem p = build_elastic_contact(mesh, with_friction(block(mesh, 0.3), FrictionLaw::Coulomb, 0.3));
  for (const std::string name : {"pdas", "pgs"}) {
    auto solver_a = make_step_solver(name), solver_b = make_step_solver(name);
    auto a = make_time_scheme("backward_euler", p, *solver_a, 0.01);
    auto b = make_time_scheme("backward_euler", p, *solver_b, 0.01);
    State s;
    s.U = Eigen::VectorXd::Zero(p.n_free());
    s.V = initial_velocity(p, thrown(p));
    a->initialize(s);
    for (int k = 0; k < 30; ++k) a->step(s);
    const SchemeMemory m = a->memory();
    a->restore(m);
    State s_b = s;
    b->restore(m);
    for (int k = 0; k < 30; ++k) {
      a->step(s);
      b->step(s_b);
    }
    EXPECT_TRUE(s.U == s_b.U && s.V == s_b.V) << name;
    EXPECT_EQ(s.contact_status, s_b.contact_status) << name;
  }
}

// The nodal Tresca threshold is the traction bound's share of Γ_C, s_a = ∫ s φ_a: its
// sum is ∫_{Γ_C} s (exact for s affine along the side: P1 traces), the two end vertices
// get half an interior one's for a constant s; Coulomb's μ is the value at the vertex.
TEST(Friction, NodalThresholdsAndCoefficients) {
  const Mesh mesh = unit_square_mesh(4);
  ElasticContactData d = with_friction(block(mesh, 0.0), FrictionLaw::Tresca, 0.0);
  d.obstacles[0].friction.threshold = [](const Point& x, double) { return 2.0 + x.x; };
  const ConstrainedProblem p = build_elastic_contact(mesh, d);
  double sum = 0.0;
  for (const FrictionNode& node : p.friction) sum += node.threshold;
  EXPECT_NEAR(sum, 2.5, 1e-13);  // ∫₀¹ (2 + x) dx
  d.obstacles[0].friction.threshold = constant(3.0);
  const ConstrainedProblem q = build_elastic_contact(mesh, d);
  for (const FrictionNode& node : q.friction) {
    const double x = mesh.vertices[q.contact_nodes[node.node].vertex].x;
    EXPECT_NEAR(node.threshold, (x == 0.0 || x == 1.0) ? 3.0 / 8 : 3.0 / 4, 1e-14) << x;
  }
  ElasticContactData c = with_friction(block(mesh, 0.0), FrictionLaw::Coulomb, 0.0);
  c.obstacles[0].friction.mu = [](const Point& x, double) { return 0.1 + x.x; };
  const ConstrainedProblem r = build_elastic_contact(mesh, c);
  for (const FrictionNode& node : r.friction)
    EXPECT_EQ(node.mu, 0.1 + mesh.vertices[r.contact_nodes[node.node].vertex].x);
}
