// test_qp_obstacle.cpp — the static membrane obstacle problem through the step solvers,
// against FreeFEM + ff-Ipopt.
//
//   min ½ ∫|∇u|² − ∫ f u,  P1 on the unit square (n × n cells, FreeFEM's square(n,n)),
//   f = −0.6, u = 0.02 on the boundary, u ≥ 0 at the vertices   (seed eq. 16, G = −I)
//
// The reference numbers (energy ½UᵀAU − LᵀU of the full field, min, max and sum of U,
// the vertex values) are stored in data/reference/static_obstacle_n{10,20}.csv, produced
// by reference_scripts/static_obstacle.edp (command in scripts/refresh-references.sh).
// Required agreement: 1e-6 relative (docs/verification.md, FreeFEM); the measured
// agreement is printed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/fe/fe_space.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/qp/step_solver.hpp"
#include "cdyn/qp/pdas/pdas.hpp"

namespace {

using Eigen::VectorXd;

struct Reference {
  double energy = 0, umin = 0, umax = 0, usum = 0;
  int contact = 0;
  std::vector<double> x, y, u;
};

// The stored references, or, when CDYN_REFERENCE_DIR is set, the CSVs that the
// `reference` label has just produced by running FreeFEM live (tests/reference).
Reference read_reference(int n) {
  const char* live = std::getenv("CDYN_REFERENCE_DIR");
  const std::string dir = live ? std::string(live) : std::string(CDYN_SOURCE_DIR) + "/data/reference";
  const std::string path = dir + "/static_obstacle_n" + std::to_string(n) + ".csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Reference ref;
  std::string line;
  std::getline(in, line);  // header
  std::getline(in, line);
  {
    std::stringstream s(line);
    std::string field;
    std::vector<std::string> f;
    while (std::getline(s, field, ',')) f.push_back(field);
    ref.energy = std::stod(f[1]);
    ref.umin = std::stod(f[2]);
    ref.umax = std::stod(f[3]);
    ref.usum = std::stod(f[4]);
    ref.contact = std::stoi(f[5]);
  }
  std::getline(in, line);  // vertex header
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string field;
    std::vector<double> f;
    while (std::getline(s, field, ',')) f.push_back(std::stod(field));
    if (f.size() != 4) continue;
    ref.x.push_back(f[1]);
    ref.y.push_back(f[2]);
    ref.u.push_back(f[3]);
  }
  return ref;
}

// The obstacle problem as a step QP on the free (interior) vertices, with what is needed
// to rebuild the full field.
struct Obstacle {
  cdyn::Mesh mesh;
  std::unique_ptr<cdyn::FESpace> W;
  std::unique_ptr<cdyn::DirichletLift> lift;
  cdyn::SparseMatrix A;
  VectorXd L, UD;
  cdyn::BoundQP qp;

  explicit Obstacle(int n) : mesh(cdyn::unit_square_mesh(n)) {
    W = std::make_unique<cdyn::FESpace>(mesh, cdyn::Element::P1);
    A = cdyn::assemble_laplace(*W);
    L = cdyn::assemble_load(*W, [](double, double, double) { return -0.6; });
    std::vector<int> parts;
    for (const char* p : {"bottom", "right", "top", "left"}) parts.push_back(mesh.part_index(p));
    lift = std::make_unique<cdyn::DirichletLift>(*W, parts);
    UD = lift->lifting(*W, {[](double, double, double) { return 0.02; }});
    qp.S = lift->restrict(A);
    qp.S.makeCompressed();
    qp.r = lift->restrict(VectorXd(L - A * UD));  // A_ff U_f = L_f − (A U_D)_f
    qp.lower = VectorXd::Zero(qp.r.size());       // u ≥ 0 at every free vertex
    qp.upper = VectorXd::Constant(qp.r.size(), std::numeric_limits<double>::infinity());
  }
  VectorXd full(const VectorXd& X) const { return lift->extend(X, UD); }
  double energy(const VectorXd& U) const { return 0.5 * U.dot(A * U) - L.dot(U); }
};

class StaticObstacle : public ::testing::TestWithParam<int> {};

TEST_P(StaticObstacle, AllSolversAgreeWithFreeFEM) {
  const int n = GetParam();
  const Reference ref = read_reference(n);
  const Obstacle ob(n);
  ASSERT_EQ(static_cast<int>(ref.u.size()), ob.mesh.n_vertices());
  for (int v = 0; v < ob.mesh.n_vertices(); ++v) {  // same vertices, same numbering
    ASSERT_NEAR(ob.mesh.vertices[v].x, ref.x[v], 1e-14);
    ASSERT_NEAR(ob.mesh.vertices[v].y, ref.y[v], 1e-14);
  }
  const double scale = ref.umax;  // the size of u: the yardstick for min, max and vertex values
  for (const std::string& name : cdyn::step_solver_names()) {
    cdyn::QPOptions opt;
    opt.pgs_omega = 2.0 / (1.0 + std::sin(M_PI / n));  // the SOR optimum for the 5-point Laplacian
    auto solver = cdyn::make_step_solver(name, opt);
    const cdyn::QPResult res = solver->solve(ob.qp);
    EXPECT_TRUE(res.converged) << name;
    EXPECT_LE(res.kkt_residual, opt.tol) << name;
    const VectorXd U = ob.full(res.X);
    const double E = ob.energy(U);
    EXPECT_NEAR(E, ref.energy, 1e-6 * std::abs(ref.energy)) << name;
    EXPECT_NEAR(U.minCoeff(), ref.umin, 1e-6 * scale) << name;
    EXPECT_NEAR(U.maxCoeff(), ref.umax, 1e-6 * scale) << name;
    EXPECT_NEAR(U.sum(), ref.usum, 1e-6 * std::abs(ref.usum)) << name;
    int contact = 0;
    double max_diff = 0;
    for (int v = 0; v < U.size(); ++v) {
      contact += U[v] < 1e-8;
      max_diff = std::max(max_diff, std::abs(U[v] - ref.u[v]));
    }
    EXPECT_EQ(contact, ref.contact) << name;
    EXPECT_LE(max_diff, 1e-6 * scale) << name;
    // reactions: the obstacle pushes up (λ ≥ 0) where u = 0, nothing elsewhere
    for (int i : res.active) {
      EXPECT_EQ(ob.qp.lower[i], 0.0);
      EXPECT_GE(res.reaction[i], -1e-12) << name;
    }
    std::cout << "n = " << n << " " << name << ": iterations " << res.iterations << ", kkt " << res.kkt_residual
              << ", |E - E_ff|/|E_ff| = " << std::abs(E - ref.energy) / std::abs(ref.energy)
              << ", max |u - u_ff| = " << max_diff << ", contact " << contact << " (FreeFEM " << ref.contact
              << "), " << res.seconds * 1e3 << " ms\n";
    RecordProperty(name + "_iterations", res.iterations);
  }
}

INSTANTIATE_TEST_SUITE_P(FreeFEM, StaticObstacle, ::testing::Values(10, 20));

TEST(StaticObstacle, PdasColdStartIterationsAndWarmStart) {
  for (int n : {10, 20, 40, 80}) {
    const Obstacle ob(n);
    cdyn::PDASSolver pdas;
    const cdyn::QPResult cold = pdas.solve(ob.qp);
    EXPECT_TRUE(cold.converged);
    const cdyn::QPResult warm = pdas.solve(ob.qp, &cold);
    EXPECT_EQ(warm.iterations, 1) << "n = " << n;
    EXPECT_EQ(warm.active, cold.active);
    std::cout << "pdas static obstacle n = " << n << ": cold start " << cold.iterations << " iterations ("
              << cold.active.size() << " active of " << ob.qp.size() << "), warm start from the solution "
              << warm.iterations << "\n";
    RecordProperty("pdas_cold_iterations_n" + std::to_string(n), cold.iterations);
    // the discrete maximum principle for this M-matrix problem: PDAS converges monotonically
    // and without cycling (Hintermüller–Ito–Kunisch 2002, Thm 3.3): no damped iterations
    EXPECT_EQ(pdas.counters().damped_iterations, 0);
  }
}

}  // namespace
