// test_elastic_contact_3d.cpp — elastodynamic Signorini contact in space
// (problems/elastic_contact.hpp on tetrahedra):
//
//  (i)   the node-local frame [n t₁ t₂] (problems/nodal_rotation.hpp) is orthonormal with
//        n first, for every direction of n, and R round-trips;
//  (ii)  the gap comes from the geometry: the bound of a contact vertex is −(a − p)·n;
//  (iii) rotation invariance: the unit cube above the plane z = 0 (bounds on u_z, no
//        rotation) and the same cube, plane, load and velocity turned by a rotation Q
//        about a skew axis (every contact node rotated, 3 × 3 blocks) give Q U to
//        round-off, with contact active;
//  (iv)  a roller in space (u_x fixed on Γ_C, the plane's normal with parts along all
//        three axes: the two free components rotated): backward Euler keeps every
//        contact vertex on the right side of the plane, and some on it;
//  (v)   the stress of an affine displacement is exact in every tetrahedron.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "cdyn/base/error.hpp"
#include "cdyn/post/stress.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/problems/nodal_rotation.hpp"
#include "cdyn/schemes/time_scheme.hpp"

using namespace cdyn;

namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// The rotation by θ about the unit axis k (Rodrigues).
Matrix3 rotation(Point k, double theta) {
  const double c = std::cos(theta), s = std::sin(theta), C = 1.0 - c;
  return {{{c + k.x * k.x * C, k.x * k.y * C - k.z * s, k.x * k.z * C + k.y * s},
           {k.y * k.x * C + k.z * s, c + k.y * k.y * C, k.y * k.z * C - k.x * s},
           {k.z * k.x * C - k.y * s, k.z * k.y * C + k.x * s, c + k.z * k.z * C}}};
}

Point apply(const Matrix3& Q, const Point& a) {
  return {Q[0][0] * a.x + Q[0][1] * a.y + Q[0][2] * a.z, Q[1][0] * a.x + Q[1][1] * a.y + Q[1][2] * a.z,
          Q[2][0] * a.x + Q[2][1] * a.y + Q[2][2] * a.z};
}

Point transpose_apply(const Matrix3& Q, const Point& a) {
  return {Q[0][0] * a.x + Q[1][0] * a.y + Q[2][0] * a.z, Q[0][1] * a.x + Q[1][1] * a.y + Q[2][1] * a.z,
          Q[0][2] * a.x + Q[1][2] * a.y + Q[2][2] * a.z};
}

constexpr double kGap = 0.01;  // the cube's bottom above the plane

// The unit cube lifted by kGap, turned by Q about the origin.
Mesh cube(int n, const Matrix3& Q) {
  Mesh m = unit_cube_mesh(n);
  for (Point& v : m.vertices) v = apply(Q, {v.x, v.y, v.z + kGap});
  return m;
}

// Clamped on its top, pulled by gravity along −n towards the plane through Q·0 with
// normal n = Q e_z, E = 1, ν = 0.3.
ElasticContactData hanging_cube(const Mesh& mesh, const Matrix3& Q, const std::string& pair) {
  ElasticContactData d;
  d.mass = MassSpec::parse(pair);
  const Lame l = lame_parameters(1.0, 0.3);
  d.lambda = l.lambda;
  d.mu = l.mu;
  const Point n = apply(Q, {0.0, 0.0, 1.0});
  d.gravity = {-n.x, -n.y, -n.z};
  d.dirichlet_parts = {mesh.part_index("top")};
  d.contact_parts = {mesh.part_index("bottom")};
  d.obstacle_point = Point{};
  d.obstacle_normal = n;
  return d;
}

// U⁰ = 0, U̇⁰ = (1 + d − z)(−½ e_z + ⅕ x e_x + ⅒ y e_y) in the cube's own frame:
// zero on the clamped top, the bottom moving towards the plane and shearing.
State initial_state(const ConstrainedProblem& p, const Matrix3& Q) {
  auto rate = [&Q](int k) {
    return [Q, k](const Point& x, double) {
      const Point a = transpose_apply(Q, x);  // the cube's own coordinates
      const double w = 1.0 + kGap - a.z;
      const Point v = apply(Q, {0.2 * a.x * w, 0.1 * a.y * w, -0.5 * w});
      return k == 0 ? v.x : k == 1 ? v.y : v.z;
    };
  };
  State s;
  s.U = Eigen::VectorXd::Zero(p.n_free());
  s.V = initial_velocity(p, p.unknowns(p.W->interpolate(std::vector<Field>{rate(0), rate(1), rate(2)})));
  return s;
}

// max over the scalar dofs of |U_turned − Q U_ref| (each (x, y, z) triple turned).
double turned_difference(const Eigen::VectorXd& U_turned, const Eigen::VectorXd& U_ref, const Matrix3& Q) {
  double e = 0.0;
  for (Eigen::Index s = 0; 3 * s < U_ref.size(); ++s) {
    const Point q = apply(Q, {U_ref[3 * s], U_ref[3 * s + 1], U_ref[3 * s + 2]});
    e = std::max({e, std::abs(U_turned[3 * s] - q.x), std::abs(U_turned[3 * s + 1] - q.y),
                  std::abs(U_turned[3 * s + 2] - q.z)});
  }
  return e;
}

QPOptions tight() {
  QPOptions o;
  o.tol = 1e-13;
  return o;
}

const Matrix3 kIdentity = rotation({0.0, 0.0, 1.0}, 0.0);
// 35° about a skew axis: every normal component and every tangent nonzero.
const Matrix3 kTurn = rotation({1.0 / std::sqrt(14.0), 2.0 / std::sqrt(14.0), 3.0 / std::sqrt(14.0)}, 35.0 * M_PI / 180);

}  // namespace

TEST(ElasticContact3D, FrameIsOrthonormalWithTheNormalFirst) {
  std::mt19937 gen(3);
  std::normal_distribution<double> N(0.0, 1.0);
  std::vector<Point> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, {0.6, 0, 0.8}, {0, 0.6, -0.8},
                                {1e-9, 0, -1}};
  for (int k = 0; k < 20; ++k) normals.push_back({N(gen), N(gen), N(gen)});
  for (const Point& n : normals) {
    NodalRotation::Node node{0, 1, n.x, n.y};
    node.iz = 2;
    node.nz = n.z;
    const auto F = rotation_frame(node);
    const double norm = std::hypot(n.x, n.y, n.z);
    // (each entry of the frame carries a few roundings: measured |t·t − 1| ≤ 5.6e-16)
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) {
        const double dot = F[c][0] * F[d][0] + F[c][1] * F[d][1] + F[c][2] * F[d][2];
        EXPECT_NEAR(dot, c == d ? 1.0 : 0.0, 2e-15) << "n = (" << n.x << ", " << n.y << ", " << n.z << ")";
      }
    EXPECT_NEAR(F[0][0], n.x / norm, 1e-16);
    EXPECT_NEAR(F[0][1], n.y / norm, 1e-16);
    EXPECT_NEAR(F[0][2], n.z / norm, 1e-16);
    // right-handed: t₁ × t₂ = n
    EXPECT_NEAR(F[1][1] * F[2][2] - F[1][2] * F[2][1], F[0][0], 2e-15);
  }
  NodalRotation rot;
  NodalRotation::Node a{0, 1, 1.0, 2.0}, b{4, 6, -0.3, 0.1};
  a.iz = 2;
  a.nz = 2.0;
  b.iz = 5;
  b.nz = 0.7;
  rot.nodes = {a, b};
  const SparseMatrix R = rotation_matrix(rot, 8);
  const Eigen::MatrixXd Rd(R);
  EXPECT_LE((Rd.transpose() * Rd - Eigen::MatrixXd::Identity(8, 8)).norm(), 1e-15);
  Eigen::VectorXd u(8);
  u << 1.0 / 3, 2.0 / 3, 2.0 / 3, 7, 5, 6, 8, 9;
  const Eigen::VectorXd local = to_local(rot, u);
  EXPECT_NEAR(local[0], 1.0, 1e-15);  // n·u with u = n
  EXPECT_NEAR(local[1], 0.0, 1e-15);
  EXPECT_NEAR(local[2], 0.0, 1e-15);
  EXPECT_EQ(local[3], 7.0);  // not a node's unknown
  EXPECT_LE((Rd.transpose() * u - local).norm(), 1e-14);
  EXPECT_LE((to_global(rot, local) - u).norm(), 1e-14);
}

TEST(ElasticContact3D, GapComesFromTheGeometry) {
  const Mesh mesh = cube(2, kTurn);
  const ElasticContactData d = hanging_cube(mesh, kTurn, "P1+/P0");
  const ConstrainedProblem p = build_elastic_contact(mesh, d);
  ASSERT_TRUE(p.R.has_value());
  const int bottom_vertices = static_cast<int>(mesh.part_vertices(d.contact_parts).size());
  ASSERT_EQ(static_cast<int>(p.constrained.size()), bottom_vertices);  // (3 × 3 vertices on the bottom)
  const Point n = d.obstacle_normal;
  for (const auto& c : p.contact_nodes) {
    const Point& a = mesh.vertices[c.vertex];
    const int i = p.bc->free_index(p.W->vertex_dof(c.vertex, 0));  // the rotated normal unknown
    ASSERT_GE(i, 0);
    EXPECT_NEAR(p.lower[i], -(a.x * n.x + a.y * n.y + a.z * n.z), 1e-15);
    EXPECT_NEAR(p.lower[i], -kGap, 1e-15);
  }
}

TEST(ElasticContact3D, RotationInvariance) {
  // Reference: the cube over z = 0, bounds on u_z.  The turned run: the same problem in
  // coordinates turned by Q (35° about a skew axis), every contact node rotated.  The
  // runs differ by round-off only (the assembly in turned coordinates, the pivot orders,
  // steps solved to a KKT residual of 1e-13): measured max|U_turned − Q U|/max|U| below
  // 1e-12 for the well-posed pairs and backward Euler; 1e-10 leaves two decades, and
  // a wrong frame or gap would show at the size of the gap, 1e-2.
  const int n = 2, steps = 30;
  const double dt = 0.01;
  const Mesh mesh0 = cube(n, kIdentity), mesh_q = cube(n, kTurn);
  struct Case {
    const char* pair;
    const char* scheme;
  };
  for (const Case& c : {Case{"P1+/P0", "midpoint"}, Case{"P2/P1", "midpoint"}, Case{"P1/P1", "backward_euler"},
                        Case{"P1+/P0", "discrete_gradient"}}) {
    const ConstrainedProblem p0 = build_elastic_contact(mesh0, hanging_cube(mesh0, kIdentity, c.pair));
    const ConstrainedProblem pq = build_elastic_contact(mesh_q, hanging_cube(mesh_q, kTurn, c.pair));
    ASSERT_FALSE(p0.R.has_value());
    ASSERT_TRUE(pq.R.has_value());
    auto s0 = make_step_solver("pdas", tight()), sq = make_step_solver("pdas", tight());
    auto t0 = make_time_scheme(c.scheme, p0, *s0, dt), tq = make_time_scheme(c.scheme, pq, *sq, dt);
    State a = initial_state(p0, kIdentity), b = initial_state(pq, kTurn);
    t0->initialize(a);
    tq->initialize(b);
    double err = 0.0, scale = 0.0;
    int active_steps = 0;
    for (int k = 0; k < steps; ++k) {
      const StepStats st0 = t0->step(a);
      const StepStats stq = tq->step(b);
      EXPECT_EQ(st0.active, stq.active) << c.pair << " " << c.scheme << " step " << k;
      active_steps += st0.active > 0;
      const Eigen::VectorXd U = p0.full(a.U);
      scale = std::max(scale, U.cwiseAbs().maxCoeff());
      err = std::max(err, turned_difference(pq.full(b.U), U, kTurn));
    }
    EXPECT_GE(active_steps, 5) << c.pair << " " << c.scheme << ": the cube should press on the plane";
    EXPECT_LE(err, 1e-10 * scale) << c.pair << " " << c.scheme;
    std::printf("3D rotation invariance %-7s %-18s: contact in %d/%d steps, max|U_turned - Q U|/max|U| = %.1e\n",
                c.pair, c.scheme, active_steps, steps, err / scale);
  }
}

// Every step solver on the turned cube (every contact node rotated, the bounds on its
// normal unknown): the same steps as pdas, each QP to a KKT residual of 1e-13.  The
// lumped P1 mass with backward Euler and P1+/P0 midpoint (its bubbles condensed): an
// explicit S, which pgs and nlopt need (the saddle-form pairs go to pdas and ipopt only).
TEST(ElasticContact3D, EveryStepSolverGivesTheSameSteps) {
  const Mesh mesh = cube(2, kTurn);
  for (const auto& [pair, scheme] : {std::pair{"lumped", "backward_euler"}, std::pair{"P1+/P0", "midpoint"}}) {
    const ConstrainedProblem p = build_elastic_contact(mesh, hanging_cube(mesh, kTurn, pair));
    std::vector<Eigen::VectorXd> reference;
    for (const std::string& name : step_solver_names()) {
      auto solver = make_step_solver(name, tight());
      auto t = make_time_scheme(scheme, p, *solver, 0.01);
      State s = initial_state(p, kTurn);
      t->initialize(s);
      double err = 0.0, scale = 0.0;
      int active_steps = 0;
      for (int k = 0; k < 30; ++k) {
        active_steps += t->step(s).active > 0;
        if (name == "pdas") reference.push_back(s.U);
        scale = std::max(scale, reference[k].lpNorm<Eigen::Infinity>());
        err = std::max(err, (s.U - reference[k]).lpNorm<Eigen::Infinity>());
      }
      EXPECT_GE(active_steps, 5) << pair << " " << name;
      // each step to KKT 1e-13 of |X|: measured ≤ 5e-14 of max|U| with backward Euler,
      // 2.8e-13 (ipopt, nlopt) and 5.6e-11 (pgs, its residual checked every 10 sweeps)
      // with the midpoint, whose full step 2U^{n+½} − Uⁿ carries each step's error on;
      // a wrong bound or frame would show at the size of the gap, 1e-2 of max|U|
      EXPECT_LE(err, 5e-10 * scale) << pair << " " << name;
      std::printf("3D %-6s %-15s %-6s: max|U - U_pdas|/max|U| = %.1e\n", pair, scheme, name.c_str(), err / scale);
    }
  }
}

TEST(ElasticContact3D, RollerStaysOnTheRightSideOfThePlane) {
  // The cube over a plane with normal n = (0.48, 0.6, 0.64) through (0, 0, −0.3), its
  // bottom held at u_x = 0.02 (a roller: y and z free, rotated to n's part along them),
  // pushed down by gravity −e_z.  Backward Euler: (a + u(a) − p)·n ≥ −tol at every
  // contact vertex and step, = 0 (to the tolerance) at some.
  const Mesh mesh = cube(2, kIdentity);
  ElasticContactData d = hanging_cube(mesh, kIdentity, "P1/P1");
  d.dirichlet_parts = {mesh.part_index("bottom")};
  d.dirichlet_components = {0};
  d.dirichlet_value[0] = [](const Point&, double) { return 0.02; };
  d.gravity = {0.0, 0.0, -2.0};
  const Point n{0.48, 0.6, 0.64}, p{0.0, 0.0, -0.3};
  d.obstacle_normal = n;
  d.obstacle_point = p;
  const ConstrainedProblem P = build_elastic_contact(mesh, d);
  ASSERT_TRUE(P.R.has_value());
  ASSERT_EQ(P.constrained.size(), mesh.part_vertices(d.contact_parts).size());
  auto solver = make_step_solver("pdas", tight());
  auto scheme = make_time_scheme("backward_euler", P, *solver, 0.05);
  State s;
  s.U = Eigen::VectorXd::Zero(P.n_free());
  s.V = Eigen::VectorXd::Zero(P.mass->n_velocity());
  double lowest = 1e300;
  for (int k = 0; k < 40; ++k) {
    scheme->step(s);
    const Eigen::VectorXd U = P.full(s.U);
    for (const auto& c : P.contact_nodes) {
      const Point& a = mesh.vertices[c.vertex];
      const double x[3] = {a.x + U[P.W->vertex_dof(c.vertex, 0)], a.y + U[P.W->vertex_dof(c.vertex, 1)],
                           a.z + U[P.W->vertex_dof(c.vertex, 2)]};
      EXPECT_NEAR(U[P.W->vertex_dof(c.vertex, 0)], 0.02, 1e-15);  // the roller holds u_x
      const double distance = (x[0] - p.x) * n.x + (x[1] - p.y) * n.y + (x[2] - p.z) * n.z;
      EXPECT_GE(distance, -1e-10) << "vertex " << c.vertex << " step " << k;
      lowest = std::min(lowest, distance);
    }
  }
  EXPECT_LE(lowest, 1e-10);  // the cube did reach the plane
}

TEST(ElasticContact3D, AffineDisplacementGivesTheExactStress) {
  // u(x) = G x with a full (non-symmetric) G: ε = ½(G + Gᵀ), σ = λ tr ε I + 2μ ε in
  // every tetrahedron, for P1, P1+ and P2 (all contain the affine fields).
  const double G[3][3] = {{0.3, -0.2, 0.5}, {0.1, -0.4, 0.25}, {-0.6, 0.35, 0.2}};
  const double lambda = 2.0, mu = 0.7;
  const Mesh mesh = unit_cube_mesh(2);
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(mesh, e, 3);
    std::vector<Field> u;
    for (int k = 0; k < 3; ++k)
      u.push_back([&G, k](const Point& x, double) { return G[k][0] * x.x + G[k][1] * x.y + G[k][2] * x.z; });
    const std::vector<StressState> cells = cell_stress(W, W.interpolate(u), lambda, mu);
    const double tr = G[0][0] + G[1][1] + G[2][2];
    for (const StressState& s : cells) {
      EXPECT_NEAR(s.epsilon.xz, 0.5 * (G[0][2] + G[2][0]), 1e-14);
      EXPECT_NEAR(s.epsilon.yz, 0.5 * (G[1][2] + G[2][1]), 1e-14);
      EXPECT_NEAR(s.sigma.zz, lambda * tr + 2 * mu * G[2][2], 1e-13);
      EXPECT_NEAR(s.sigma.xy, mu * (G[0][1] + G[1][0]), 1e-13);
      EXPECT_NEAR(s.sigma.yz, mu * (G[1][2] + G[2][1]), 1e-13);
    }
    // σ_vM of a hydrostatic state is 0, of a pure shear σ_xz = τ is √3 τ
    EXPECT_EQ(von_mises({-2.0, -2.0, -2.0, 0.0, 0.0, 0.0}), 0.0);
    EXPECT_DOUBLE_EQ(von_mises({0.0, 0.0, 0.0, 0.0, 1.5, 0.0}), 1.5 * std::sqrt(3.0));
  }
}
