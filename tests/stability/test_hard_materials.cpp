// test_hard_materials.cpp — plane-strain elasticity near incompressibility and with a
// very stiff or very soft body against the rigid plane (problems/elastic_contact.hpp).
//
// The body: the block [0, 1] × [d, 1 + d] (d = 0.01, n = 8), clamped on its top,
// under gravity (f = (0, −1)), its bottom in contact with the plane y = 0.
//
// Nearly incompressible (ν = 0.49, 0.499, E = 1): locking.  The P1 displacement
// space cannot represent nearly divergence-free fields on a triangulation (the
// discrete divergence-free subspace is almost trivial), so its static sag under
// gravity falls far below the true one as ν → ½, while P2 keeps most of it.  Shown:
// the static sag (no obstacle, A U = L) of P1 and P1+ relative to P2, for ν = 0.3,
// 0.49, 0.499; asserted: the P1/P2 ratio falls strictly as ν → ½ (the signature of
// locking: the P1 error constant grows with λ/μ; measured 0.988, 0.816, 0.646 at
// n = 8; the P1+ bubble changes nothing here, its sag equals P1's to 4 digits).  Expected for the dynamics with contact
// (P1+/P0, backward Euler and midpoint_end, dt = 0.01, 100 steps): finite, the
// constrained U^{n+1} feasible to 1e-12 (QP tolerance 1e-13 relative to |U| ≲ 1), J
// never above J0 (5e-12·|J0|: round-off of 100 steps, 100 ε κ(S)), QP iterations bounded (≤ 10;
// measured in docs/stability.md).
// Very stiff / very soft body (E = 10⁴ and 10⁻⁴, ν = 0.3): the step matrix
// S = Mc² + A is dominated by A (cond(S) ~ cond(A)) or by M; the same expectations.
// (The stiff block, clamped on top, only vibrates by 1e-4 and never reaches the plane
// at d = 0.01; the soft one falls onto it and stays.)
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "cdyn/problems/elastic_contact.hpp"
#include "stability_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::stability;

namespace {

constexpr double kGap = 0.01;

Mesh block(int n) {
  Mesh m = unit_square_mesh(n);
  for (Point& v : m.vertices) v.y += kGap;
  return m;
}

ElasticContactData hanging_block(const Mesh& mesh, const Method& m, double E, double nu, bool obstacle) {
  ElasticContactData d;
  d.mass = cdyn::MassSpec::parse(m.velocity, m.W);
  const Lame l = lame_parameters(E, nu);
  d.lambda = l.lambda;
  d.mu = l.mu;
  d.f = {zero_field, [](double, double, double) { return -1.0; }};
  d.dirichlet_parts = {mesh.part_index("top")};
  d.contact_parts = {mesh.part_index("bottom")};
  d.obstacle_point = {0.0, 0.0};
  d.obstacle_normal = {0.0, 1.0};
  d.obstacle = obstacle;
  return d;
}

// Largest |u_y| at the vertices of the static solution A U = L (no obstacle).
double static_sag(const Mesh& mesh, Element W, double nu) {
  const ConstrainedProblem p = build_elastic_contact(mesh, hanging_block(mesh, {W, "P0"}, 1.0, nu, false));
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(p.A);
  const Eigen::VectorXd U = p.full(ldlt.solve(p.load(0.0)));
  double sag = 0.0;
  for (int v = 0; v < mesh.n_vertices(); ++v) sag = std::max(sag, std::abs(U[p.W->vertex_dof(v, 1)]));
  return sag;
}

RunRecord falling_block(const Mesh& mesh, const std::string& scheme_name, double E, double nu) {
  const ConstrainedProblem p = build_elastic_contact(mesh, hanging_block(mesh, {Element::P1Bubble, "P0"}, E, nu, true));
  auto solver = make_step_solver("pdas", tight());
  auto scheme = make_time_scheme(scheme_name, p, *solver, 0.01);
  State s;
  s.U = Eigen::VectorXd::Zero(p.n_free());
  // the bottom moving down at speed 1 − (y − d): it reaches the plane in the first steps
  s.V = initial_velocity(p, p.unknowns(p.W->interpolate(std::vector<Field>{
                                zero_field, [](double, double y, double) { return -(1.0 + kGap - y); }})));
  const RunRecord r = run(*scheme, p, s, 100);
  char what[128];
  std::snprintf(what, sizeof what, "block P1+/P0 %s E = %g nu = %g", scheme_name.c_str(), E, nu);
  print(what, r);
  return r;
}

void expect_stable(const RunRecord& r, const std::string& what) {
  ASSERT_TRUE(r.finite) << what;
  EXPECT_LE(r.max_violation, 1e-12) << what;
  // round-off of 100 steps: 100 ε κ(S) ≈ 4.8e-12 with κ(S) = 216 for the stiff block (the
  // largest; dense eigenvalues of S = 2c²M + A/2); measured 2.0e-12 (E = 1e4, midpoint_end)
  EXPECT_LE(r.growth(), 5e-12 * std::abs(r.J0)) << what;
  EXPECT_LE(r.max_iterations, 10) << what;
}

}  // namespace

TEST(NearlyIncompressible, P1LocksAsNuTendsToOneHalf) {
  const Mesh mesh = block(8);
  double previous_ratio = 1.0 + 1e-9;  // P1 ⊂ P2: the P1 sag is the smaller (energy minimisation)
  for (double nu : {0.3, 0.49, 0.499}) {
    const double p1 = static_sag(mesh, Element::P1, nu), p1b = static_sag(mesh, Element::P1Bubble, nu),
                 p2 = static_sag(mesh, Element::P2, nu);
    std::printf("static sag nu = %g: P2 %.4e, P1 %.4e (P1/P2 = %.3f), P1+ %.4e (P1+/P2 = %.3f)\n", nu, p2, p1, p1 / p2,
                p1b, p1b / p2);
    EXPECT_LT(p1 / p2, previous_ratio) << "nu = " << nu;
    previous_ratio = p1 / p2;
  }
}

TEST(NearlyIncompressible, ContactDynamicsStayStable) {
  const Mesh mesh = block(8);
  for (double nu : {0.49, 0.499})
    for (const std::string scheme : {"backward_euler", "midpoint_end"})
      expect_stable(falling_block(mesh, scheme, 1.0, nu), scheme + " nu = " + std::to_string(nu));
}

TEST(ExtremeStiffness, VeryStiffAndVerySoftBodiesAgainstThePlane) {
  const Mesh mesh = block(8);
  for (double E : {1e4, 1e-4})
    for (const std::string scheme : {"backward_euler", "midpoint_end"})
      expect_stable(falling_block(mesh, scheme, E, 0.3), scheme + " E = " + std::to_string(E));
}

// The time-integration question (docs/schemes.md, "When the midpoint rule gains
// energy"): a nearly incompressible block (ν = 0.4999, λ/μ = 5000) thrown at the plane.
// The midpoint rule conserves J exactly between switches of the active set and errs on
// the switching steps by up to L|Δq|²/4, L the Lipschitz constant of the reduced force —
// large for a stiff material: here it leaves the impact with more energy than it had
// (printed).  discrete_gradient keeps J to round-off through the same impacts (asserted:
// 1e-9 J0 over 100 steps; measured in docs/stability.md) and, like every reconstructing
// scheme, leaves no penetration at the full steps.
TEST(NearlyIncompressible, DiscreteGradientNeverGainsEnergy) {
  const Mesh mesh = block(8);
  const RunRecord mp = falling_block(mesh, "midpoint", 1.0, 0.4999);
  const RunRecord dg = falling_block(mesh, "discrete_gradient", 1.0, 0.4999);
  ASSERT_TRUE(mp.finite && dg.finite);
  std::printf("nu = 0.4999: midpoint max J/J0 = %.4f, discrete_gradient max |J - J0|/J0 = %.2e\n", mp.J_max / mp.J0,
              std::max(dg.J_max - dg.J0, dg.J0 - dg.J_min) / dg.J0);
  EXPECT_GT(dg.active_changes, 1);
  EXPECT_LE(std::max(dg.J_max - dg.J0, dg.J0 - dg.J_min), 1e-9 * std::abs(dg.J0));
  EXPECT_LE(dg.max_violation, 1e-12);
}
