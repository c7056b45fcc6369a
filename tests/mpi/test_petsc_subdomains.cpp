// test_petsc_subdomains.cpp — the step QP summed from the subdomains' shares
// (qp/petsc/backend.hpp, make_petsc_subdomain_solver) against the whole problem's QP
// solved by the native pdas, on one process and on two.
//
// Every rank runs every test (no rank commands the others): it builds the elastic
// contact problem on the whole mesh (the reference, solved serially on each rank) and on
// the sub-mesh of its own slab of cells (mesh/sub_mesh.hpp), condenses its share of the
// step matrix S = A + k M and of r = k M w + L (each a sum over cells, the bubbles each in
// one cell: tests/unit/test_sub_mesh.cpp), and the ranks solve the summed QP together.
// Each rank's unknowns must get the whole QP's solution to 1e-8 of ‖X‖∞ (the KKT
// tolerance's effect at tol = 1e-12, as tests/mpi/test_petsc_step_solvers.cpp), the same
// held unknowns, its reaction, and a KKT residual ≤ tol; a warm start from the solution
// takes one iteration.  The body is clamped on its left side; the plane is inclined
// (rotated unknowns at the contact nodes) and rises towards the free end, onto which
// gravity bends the body: a part of the contact nodes is held (near the free end, the
// last rank's).  Then the schemes stepped on the ranks' cells against the whole
// problem's serial run, the schemes refused on shares, and a bad share on one rank.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/mesh/sub_mesh.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/problems/subdomain.hpp"
#include "cdyn/qp/condensation.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "cdyn/schemes/time_scheme.hpp"

namespace cdyn {
namespace {

constexpr double kTol = 1e-12;
constexpr double k = 100.0;  // m/dt² of a step with dt = 0.1

ElasticContactData data(int dim, const MassSpec& mass) {
  ElasticContactData d;
  d.mass = mass;
  const Lame lame = lame_parameters(1.0, 0.3);
  d.lambda = lame.lambda, d.mu = lame.mu;
  d.gravity = {0.0, dim == 2 ? -3.0 : 0.0, dim == 3 ? -3.0 : 0.0};
  d.dirichlet_parts = {3};  // "left"
  d.contact_parts = {dim == 2 ? 0 : 4};  // "bottom"
  // a plane rising towards x = 1, 0.002 below the body's corner there
  d.obstacle_point = {1.0, dim == 2 ? -0.002 : 0.0, dim == 3 ? -0.002 : 0.0};
  d.obstacle_normal = dim == 2 ? Point{-0.1, 1.0, 0.0} : Point{-0.1, 0.0, 1.0};
  return d;
}

// The step QP of a problem: S = A + k M and r = k M w + L(0) with w = −0.005 on every
// unknown, its bubbles condensed (the blocks only: the rule for single unknowns reads
// S's pattern, which a subdomain's share does not have; the same on the whole problem
// and on a share).
struct StepQP {
  StaticCondensation condensation;
  BoundQP qp;
};
StepQP step_qp(const ConstrainedProblem& p) {
  const SparseMatrix M = *p.mass->matrix();
  SparseMatrix S = p.A + k * M;
  S.makeCompressed();
  const Eigen::VectorXd r = k * (M * Eigen::VectorXd::Constant(p.n_free(), -0.005)) + p.load(0.0);
  StaticCondensation c(S, p.lower, p.upper, bubble_unknowns(p), /*single_unknowns=*/false);
  BoundQP qp;
  qp.S = c.S_c();
  qp.r = c.reduce(r);
  qp.lower = c.kept(p.lower), qp.upper = c.kept(p.upper);
  return {std::move(c), std::move(qp)};
}

void expect_subdomains_solve_the_whole(const Mesh& mesh, const MassSpec& mass) {
  const int me = petsc::rank(), ranks = petsc::size();
  const ElasticContactData d = data(mesh.dim, mass);
  const ConstrainedProblem whole = build_elastic_contact(mesh, d);
  const StepQP W = step_qp(whole);
  QPOptions options;
  options.tol = kTol;
  const QPResult reference = make_step_solver("pdas", options)->solve(W.qp);
  ASSERT_GT(reference.active.size(), 0u);
  ASSERT_LT(reference.active.size(), whole.constrained.size());

  // this rank's slab of cells, its share of the QP and where its unknowns sit
  const SubMesh sub = sub_mesh(mesh, slab_cells(mesh, me, ranks));
  const ConstrainedProblem part = build_elastic_contact(sub.mesh, d);
  const StepQP R = step_qp(part);
  const std::vector<int> free_in_whole = unknowns_in_whole(*whole.W, *whole.bc, part, sub);
  std::vector<int> kept_of(W.condensation.n(), -1);
  const std::vector<int>& kept_whole = W.condensation.kept_unknowns();
  for (std::size_t i = 0; i < kept_whole.size(); ++i) kept_of[kept_whole[i]] = static_cast<int>(i);
  std::vector<int> global;
  for (int i : R.condensation.kept_unknowns()) global.push_back(kept_of[free_in_whole[i]]);

  auto solver = petsc::make_petsc_subdomain_solver(global, options);
  const QPResult result = solver->solve(R.qp);
  const double scale = reference.X.lpNorm<Eigen::Infinity>();
  const double reaction_scale = reference.reaction.lpNorm<Eigen::Infinity>();
  double dX = 0, dl = 0;
  int held = 0, held_reference = 0;
  for (std::size_t i = 0; i < global.size(); ++i) {
    dX = std::max(dX, std::abs(result.X[i] - reference.X[global[i]]));
    dl = std::max(dl, std::abs(result.reaction[i] - reference.reaction[global[i]]));
    held_reference += std::count(reference.active.begin(), reference.active.end(), global[i]) > 0;
  }
  held = static_cast<int>(result.active.size());
  std::printf("rank %d of %d: %zu of %d unknowns, %d held; |dX| = %.2e of %.2e, |dλ| = %.2e of %.2e, KKT %.2e, "
              "%d iterations\n",
              me, ranks, global.size(), W.qp.size(), held, dX, scale, dl, reaction_scale, result.kkt_residual,
              result.iterations);
  EXPECT_LE(dX, 1e-8 * scale);
  EXPECT_LE(dl, 1e-6 * reaction_scale);
  EXPECT_EQ(held, held_reference);
  EXPECT_LE(result.kkt_residual, kTol);

  // from the solution: one iteration, the same solution
  const QPResult again = solver->solve(R.qp, &result);
  EXPECT_EQ(again.iterations, 1);
  EXPECT_LE((again.X - result.X).lpNorm<Eigen::Infinity>(), 1e-8 * scale);
}

// The time loop on subdomains: every rank steps the scheme on its own cells' problem
// with the subdomains' solver (the scheme condenses the bubbles of its share and tells
// the solver which unknowns it keeps), the body pushed onto the plane; after each step
// its displacement is the whole problem's serial run's (native pdas) on its unknowns,
// and the energy summed over the ranks is the whole's.  Measured: see the output.
void expect_time_loops_agree(const Mesh& mesh, const MassSpec& mass, const std::string& scheme,
                             bool reconstruct = false) {
  const int me = petsc::rank(), ranks = petsc::size();
  const ElasticContactData d = data(mesh.dim, mass);
  const ConstrainedProblem whole = build_elastic_contact(mesh, d);
  const SubMesh sub = sub_mesh(mesh, slab_cells(mesh, me, ranks));
  const ConstrainedProblem part = build_elastic_contact(sub.mesh, d);
  const std::vector<int> labels = unknowns_in_whole(*whole.W, *whole.bc, part, sub);

  QPOptions options;
  options.tol = kTol;
  auto serial = make_step_solver("pdas", options);
  auto shared = petsc::make_petsc_subdomain_solver(labels, options);
  SchemeParameters parameters;
  parameters.reconstruct = reconstruct;  // midpoint: eq. (14)'s QP summed from the shares too
  parameters.tol = kTol;
  const double dt = 0.02;
  auto W = make_time_scheme(scheme, whole, *serial, dt, parameters);
  auto R = make_time_scheme(scheme, part, *shared, dt, parameters);
  State w, r;
  w.U = Eigen::VectorXd::Zero(whole.n_free());
  w.V = whole.mass->velocity(Eigen::VectorXd::Constant(whole.n_free(), -0.1));
  r.U = Eigen::VectorXd::Zero(part.n_free());
  r.V = part.mass->velocity(Eigen::VectorXd::Constant(part.n_free(), -0.1));  // the same field
  double dU = 0, dJ = 0;
  int most_held = 0;
  for (int step = 0; step < 25; ++step) {
    most_held = std::max(most_held, W->step(w).active);
    R->step(r);
    for (int i = 0; i < part.n_free(); ++i) dU = std::max(dU, std::abs(r.U[i] - w.U[labels[i]]));
    const double J = petsc::sum_over_ranks(R->energy(r).total()), J_whole = W->energy(w).total();
    dJ = std::max(dJ, std::abs(J - J_whole) / std::abs(J_whole));
  }
  std::printf("rank %d of %d, %s%s: max |dU| = %.2e of %.2e, |dJ|/|J| = %.2e, %d held at most\n", me, ranks,
              scheme.c_str(), reconstruct ? " (full steps reconstructed)" : "", dU, w.U.lpNorm<Eigen::Infinity>(), dJ,
              most_held);
  EXPECT_GT(most_held, 0);
  EXPECT_LE(dU, 1e-8 * w.U.lpNorm<Eigen::Infinity>());
  EXPECT_LE(dJ, 1e-9);
}

TEST(Subdomains, SolveTheWholeStepQPInThePlane) {
  expect_subdomains_solve_the_whole(unit_square_mesh(12), MassSpec::pair(Element::P1Bubble, Element::P0));
}

TEST(Subdomains, SolveTheWholeStepQPInSpace) {
  expect_subdomains_solve_the_whole(unit_cube_mesh(4), MassSpec::pair(Element::P1Bubble, Element::P0));
}

TEST(Subdomains, SolveTheWholeStepQPWithTheConsistentMass) {
  expect_subdomains_solve_the_whole(unit_square_mesh(12), MassSpec::parse("consistent", Element::P1));
}

TEST(Subdomains, TimeLoopsAgreeWithTheWholeProblemsInThePlane) {
  for (const std::string scheme : {"backward_euler", "midpoint"})
    expect_time_loops_agree(unit_square_mesh(12), MassSpec::pair(Element::P1Bubble, Element::P0), scheme);
  expect_time_loops_agree(unit_square_mesh(12), MassSpec::pair(Element::P1Bubble, Element::P0), "midpoint", true);
}

TEST(Subdomains, TimeLoopsAgreeWithTheWholeProblemsInSpace) {
  expect_time_loops_agree(unit_cube_mesh(4), MassSpec::pair(Element::P1Bubble, Element::P0), "midpoint");
  expect_time_loops_agree(unit_cube_mesh(4), MassSpec::pair(Element::P1Bubble, Element::P0), "midpoint", true);
}

// A share that fails the input checks on one rank (a NaN in r on the last) stops every
// rank with an InputError, none left waiting in a collective call.
TEST(Subdomains, ABadShareOnOneRankStopsEveryRank) {
  const Mesh mesh = unit_square_mesh(6);
  const ElasticContactData d = data(2, MassSpec::pair(Element::P1Bubble, Element::P0));
  const int me = petsc::rank(), ranks = petsc::size();
  const SubMesh sub = sub_mesh(mesh, slab_cells(mesh, me, ranks));
  const ConstrainedProblem part = build_elastic_contact(sub.mesh, d);
  const FESpace W(mesh, Element::P1Bubble, 2);
  const DirichletLift bc(W, d.dirichlet_parts);
  StepQP R = step_qp(part);
  std::vector<int> global;
  const std::vector<int> labels = unknowns_in_whole(W, bc, part, sub);
  for (int i : R.condensation.kept_unknowns()) global.push_back(labels[i]);
  auto solver = petsc::make_petsc_subdomain_solver(global, QPOptions{});
  if (me == ranks - 1) R.qp.r[0] = NAN;
  EXPECT_THROW(solver->solve(R.qp), InputError) << "rank " << me;
}

// The schemes not yet checked on subdomains are refused, naming the scheme.
TEST(Subdomains, OtherSchemesAreRefused) {
  const Mesh mesh = unit_square_mesh(4);
  const ElasticContactData d = data(2, MassSpec::pair(Element::P1Bubble, Element::P0));
  const SubMesh sub = sub_mesh(mesh, slab_cells(mesh, petsc::rank(), petsc::size()));
  const ConstrainedProblem part = build_elastic_contact(sub.mesh, d);
  const FESpace W(mesh, Element::P1Bubble, 2);
  const DirichletLift bc(W, d.dirichlet_parts);
  auto shared = petsc::make_petsc_subdomain_solver(unknowns_in_whole(W, bc, part, sub), QPOptions{});
  for (const std::string scheme : {"newmark", "energy_conserving", "paoli_schatzman"}) {
    try {
      make_time_scheme(scheme, part, *shared, 0.01);
      ADD_FAILURE() << scheme << " was not refused";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(scheme), std::string::npos) << e.what();
    }
  }
  // the midpoint rule of P1+/P1, whose full steps are reconstructed by multipliers in
  // saddle form (not split): refused when the scheme is made, before any solve
  const ConstrainedProblem saddle =
      build_elastic_contact(sub.mesh, data(2, MassSpec::pair(Element::P1Bubble, Element::P1)));
  auto shared_saddle = petsc::make_petsc_subdomain_solver(unknowns_in_whole(W, bc, saddle, sub), QPOptions{});
  try {
    make_time_scheme("midpoint", saddle, *shared_saddle, 0.01);
    ADD_FAILURE() << "P1+/P1's reconstruction was not refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("multipliers"), std::string::npos) << e.what();
  }
}

TEST(Subdomains, TimeLoopsAgreeWithTheConsistentMass) {
  expect_time_loops_agree(unit_square_mesh(12), MassSpec::parse("consistent", Element::P1), "backward_euler");
}

}  // namespace
}  // namespace cdyn

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  cdyn::petsc::initialize();
  return cdyn::petsc::end_process(RUN_ALL_TESTS());
}
