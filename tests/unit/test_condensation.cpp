// test_condensation.cpp — static condensation of the bubbles (qp/condensation.hpp): it picks
// the bubbles of P1+/P0 and nothing else, makes no fill, and is an identity — the
// condensed QP and the full QP have the same solution and reaction, and a time loop
// with and without it gives the same states to round-off; in elasticity it takes each
// cell's bubble as one block of unknowns (one a component), which no single-unknown rule
// could take.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <iostream>

#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/qp/condensation.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"
#include "cdyn/qp/pdas/pdas.hpp"
#include "scheme_fixtures.hpp"

namespace {

using namespace cdyn;
using cdyn::testing::initial_state;
using cdyn::testing::membrane;

// S = 4 M/dt² + A of the midpoint scheme (dt = 0.001) for a pair on the membrane.
SparseMatrix midpoint_S(const ConstrainedProblem& p, double dt = 1e-3) {
  SparseMatrix S = p.A + (4.0 / (dt * dt)) * *p.mass->matrix();
  S.makeCompressed();
  return S;
}

// The nonzeros of S restricted to the kept unknowns.
long kept_block_nonzeros(const SparseMatrix& S, const StaticCondensation& c) {
  long nnz = 0;
  for (int j = 0; j < S.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(S, j); it; ++it) nnz += !c.condenses(j) && !c.condenses(it.row());
  return nnz;
}

TEST(Condensation, PicksExactlyTheBubblesOfP1PlusP0WithoutFill) {
  const Mesh mesh = unit_square_mesh(8);
  const ConstrainedProblem p = membrane(mesh, {Element::P1Bubble, "P0"}, true);
  const SparseMatrix S = midpoint_S(p);
  const StaticCondensation c(S, p.lower, p.upper);
  // One bubble per triangle, 2n² of them; the free vertices (n−1)² are all kept.
  EXPECT_EQ(c.n_condensed(), mesh.n_cells());
  EXPECT_EQ(c.n_kept(), 7 * 7);
  for (int i = 0; i < p.n_free(); ++i)
    if (c.condenses(i)) {
      EXPECT_FALSE(std::isfinite(p.lower[i]));  // never a constrained unknown
    }
  // No fill: S_c has the pattern of S_vv.
  EXPECT_EQ(c.S_c().nonZeros(), kept_block_nonzeros(S, c));

  // The same without the obstacle: the vertices are unbounded then, but an interior
  // vertex's neighbours are not a clique, so the choice is the same.
  const ConstrainedProblem free = membrane(mesh, {Element::P1Bubble, "P0"}, false);
  EXPECT_EQ(StaticCondensation(midpoint_S(free), free.lower, free.upper).n_condensed(), mesh.n_cells());

  // P1 with the consistent mass, unconstrained: only the two corner vertices (n−1, 1)
  // and (1, n−1), whose two free neighbours are joined by a diagonal of the mesh
  // (square(n) splits along the lower-left to upper-right diagonal); every other
  // free vertex has a ring of neighbours, not a clique.
  const ConstrainedProblem p1 = membrane(mesh, {Element::P1, "consistent"}, false);
  EXPECT_EQ(StaticCondensation(midpoint_S(p1), p1.lower, p1.upper).n_condensed(), 2);
}

// S_c against the Schur complement computed densely, and the QP identity: the PDAS
// solution of the condensed QP, expanded, is the PDAS solution of the full QP.
TEST(Condensation, CondensedQPHasTheSameSolutionAndReaction) {
  const Mesh mesh = unit_square_mesh(6);
  const ConstrainedProblem p = membrane(mesh, {Element::P1Bubble, "P0"}, true);
  const SparseMatrix S = midpoint_S(p);
  const StaticCondensation c(S, p.lower, p.upper);
  const int n = p.n_free();

  // dense Schur complement S_vv − S_vb S_bb⁻¹ S_bv
  std::vector<int> v, b;
  for (int i = 0; i < n; ++i) (c.condenses(i) ? b : v).push_back(i);
  const Eigen::MatrixXd Sd(S);
  Eigen::MatrixXd Svv(v.size(), v.size()), Svb(v.size(), b.size()), Sbb(b.size(), b.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = 0; j < v.size(); ++j) Svv(i, j) = Sd(v[i], v[j]);
    for (std::size_t j = 0; j < b.size(); ++j) Svb(i, j) = Sd(v[i], b[j]);
  }
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) Sbb(i, j) = Sd(b[i], b[j]);
  EXPECT_EQ((Sbb - Eigen::MatrixXd(Sbb.diagonal().asDiagonal())).cwiseAbs().maxCoeff(), 0.0);  // S_bb diagonal
  const Eigen::MatrixXd Sc = Svv - Svb * Sbb.diagonal().cwiseInverse().asDiagonal() * Svb.transpose();
  // Both are sums of a few terms of size ≤ ‖S‖ (≈ 4·10⁶ |K|/dt² scale): agreement to a
  // few ulps of the largest entry.
  EXPECT_LE((Eigen::MatrixXd(c.S_c()) - Sc).cwiseAbs().maxCoeff(), 1e-14 * Sd.cwiseAbs().maxCoeff());

  // r = S w for a w of both signs: the unconstrained minimizer w dips below the
  // obstacle u ≥ 0 at about half the vertices, so many bounds are active
  BoundQP full;
  full.S = S;
  full.lower = p.lower;
  full.upper = p.upper;
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) w[i] = 0.01 * std::cos(7.0 * i);
  full.r = S * w;
  BoundQP reduced;
  reduced.S = c.S_c();
  reduced.lower = c.kept(p.lower);
  reduced.upper = c.kept(p.upper);
  reduced.r = c.reduce(full.r);
  QPOptions o;
  o.tol = 1e-13;
  // Direct solves only: this checks an identity of the condensation, to round-off, while
  // PDAS's CG stops at the KKT tolerance, which bounds the residual, not the error in X.
  o.pdas_cg_iterations = 0;
  PDASSolver a(o), d(o);
  const QPResult rf = a.solve(full), rc = d.solve(reduced);
  ASSERT_GT(rc.active.size(), 5u);
  const Eigen::VectorXd X = c.expand(rc.X, full.r);
  const Eigen::VectorXd lambda = c.expand_reaction(rc.reaction);
  // Both solve the same equations S_II X_I = r_I − S_IA X_A, one by eliminating the
  // bubbles first: they agree to round-off, relative to the solution and the load.
  const double dx = (X - rf.X).lpNorm<Eigen::Infinity>() / rf.X.lpNorm<Eigen::Infinity>();
  const double dl = (lambda - rf.reaction).lpNorm<Eigen::Infinity>() / full.r.lpNorm<Eigen::Infinity>();
  std::cout << "condensed vs full QP: |dX|/|X| = " << dx << ", |dλ|/|r| = " << dl << "\n";
  EXPECT_LE(dx, 1e-12);
  EXPECT_LE(dl, 1e-12);
  // λ_b = 0 and λ_v = S_c X_v − r_c are the full reaction S X − r (the identity behind it)
  const Eigen::VectorXd direct = S * X - full.r;
  EXPECT_LE((direct - lambda).lpNorm<Eigen::Infinity>(), 1e-12 * full.r.lpNorm<Eigen::Infinity>());
}

// A time loop through the impact (the seed's membrane, P1+/P0, midpoint and backward
// Euler): the condensed and uncondensed schemes give the same states to round-off.
TEST(Condensation, TimeLoopsAgreeWithAndWithoutCondensation) {
  const Mesh mesh = unit_square_mesh(8);
  for (const bool obstacle : {false, true})
  for (const std::string scheme : {"midpoint", "backward_euler", "midpoint_end"}) {
    const ConstrainedProblem p = membrane(mesh, {Element::P1Bubble, "P0"}, obstacle);
    QPOptions direct = cdyn::testing::tight();
    direct.pdas_cg_iterations = 0;  // direct solves only: the comparison is then round-off
    PDASSolver s1(direct), s2(direct);
    SchemeParameters with, without;
    without.condense = false;
    auto t1 = make_time_scheme(scheme, p, s1, 1e-3, with);
    auto t2 = make_time_scheme(scheme, p, s2, 1e-3, without);
    State a = initial_state(p), b = initial_state(p);
    double du = 0, dv = 0;
    int max_active = 0;
    for (int k = 0; k < 300; ++k) {  // the membrane touches at t ≈ 0.1
      const StepStats st = t1->step(a);
      t2->step(b);
      max_active = std::max(max_active, st.active);
      du = std::max(du, (a.U - b.U).lpNorm<Eigen::Infinity>() / b.U.lpNorm<Eigen::Infinity>());
      dv = std::max(dv, (a.V - b.V).lpNorm<Eigen::Infinity>() / std::max(b.V.lpNorm<Eigen::Infinity>(), 1e-3));
    }
    std::cout << scheme << (obstacle ? " (obstacle)" : " (no obstacle)") << ": max |dU|/|U| = " << du << ", |dV|/|V| = " << dv << ", active up to " << max_active
              << "\n";
    EXPECT_EQ(max_active > 0, obstacle) << scheme;  // the impact is inside the window
    // Round-off of the two elimination orders: one step differs by ≈ 1e-13 relative
    // (the QP test above: the bubble back-substitution cancels terms of size S_bb ‖U‖).
    // The midpoint rules carry such a difference forward undamped in the massless
    // modes of P1+/P0 (Ker M ≠ 0: U^{n+1} = 2U^{n+½} − Uⁿ flips their sign each
    // step), so it grows at most linearly: 300 steps × 1e-13 × 3 = 1e-10.  Measured
    // (output): 4e-11 for midpoint, 1e-12 for the dissipative backward Euler, with and
    // without contact.
    EXPECT_LE(du, 1e-10) << scheme;
    EXPECT_LE(dv, 1e-10) << scheme;
  }
}

// The CG path of the PDAS solver (QPOptions::pdas_cg_iterations) on the condensed step
// matrix, which is what it is for: a time loop through the impact with CG and with
// factor updates only gives the same states.  CG stops at ‖b − S̃y‖ ≤ 1e-14 ‖b‖, and S_c
// is well conditioned (condition O(1), docs/performance.md), so each solve is exact to
// ≈ 1e-14 relative; as in the test above the midpoint rule carries such differences
// forward undamped, 300 steps × 1e-14 × 3 ≈ 1e-11.  Measured: see the output.
TEST(Condensation, ConjugateGradientsOnTheCondensedStepGiveTheSameStates) {
  const Mesh mesh = unit_square_mesh(16);
  const ConstrainedProblem p = membrane(mesh, {Element::P1Bubble, "P0"}, true);
  QPOptions with_cg = cdyn::testing::tight(), without = with_cg;
  without.pdas_cg_iterations = 0;
  with_cg.pdas_cg_always = true;  // (at 16 × 16 cells a refactorization costs fewer flops than CG)
  PDASSolver s1(with_cg), s2(without);
  auto t1 = make_time_scheme("midpoint", p, s1, 1e-3);
  auto t2 = make_time_scheme("midpoint", p, s2, 1e-3);
  State a = initial_state(p), b = initial_state(p);
  double du = 0;
  for (int k = 0; k < 300; ++k) {
    t1->step(a);
    t2->step(b);
    du = std::max(du, (a.U - b.U).lpNorm<Eigen::Infinity>() / b.U.lpNorm<Eigen::Infinity>());
  }
  std::cout << "CG vs factor updates: max |dU|/|U| = " << du << ", CG solves " << s1.counters().cg_solves
            << " (" << s1.counters().cg_iterations << " iterations), factorizations " << s1.counters().factorizations
            << " vs " << s2.counters().factorizations << "\n";
  EXPECT_GT(s1.counters().cg_solves, 0);      // the path was taken
  EXPECT_EQ(s2.counters().cg_solves, 0);
  EXPECT_LE(du, 3e-11);
}

}  // namespace

namespace {

// A body of the unit square or cube resting at 0.01 above the plane y = 0 (z = 0 in
// space), pushed towards it: P1+/P0 elasticity, ν = 0.3, the plane inclined a little so
// that the contact nodes carry rotated unknowns.
ConstrainedProblem elastic_body(const Mesh& mesh) {
  ElasticContactData d;
  d.mass = MassSpec::pair(Element::P1Bubble, Element::P0);
  const Lame lame = lame_parameters(1.0, 0.3);
  d.lambda = lame.lambda;
  d.mu = lame.mu;
  d.contact_parts = {mesh.dim == 2 ? 0 : 4};  // "bottom"
  d.obstacle_point = {0.0, mesh.dim == 2 ? -0.01 : 0.0, mesh.dim == 3 ? -0.01 : 0.0};
  d.obstacle_normal = mesh.dim == 2 ? Point{0.1, 1.0, 0.0} : Point{0.1, 0.0, 1.0};
  return build_elastic_contact(mesh, d);
}

}  // namespace

// Elasticity: each cell's bubble unknowns (one a component) are coupled with each other
// by A, and each with one component of the cell's vertices, so that no single one has a
// clique of neighbours and the rule for single unknowns takes none; named as one block
// each (bubble_unknowns), every bubble is condensed, without fill, and S_c is the dense
// Schur complement.
TEST(Condensation, TakesEachCellsBubbleAsOneBlockInElasticity) {
  for (const Mesh& mesh : {unit_square_mesh(5), unit_cube_mesh(2)}) {
    const ConstrainedProblem p = elastic_body(mesh);
    const SparseMatrix S = midpoint_S(p);
    EXPECT_EQ(StaticCondensation(S, p.lower, p.upper).n_condensed(), 0) << "dim " << mesh.dim;
    const StaticCondensation c(S, p.lower, p.upper, bubble_unknowns(p));
    ASSERT_EQ(c.n_condensed(), mesh.dim * mesh.n_cells());
    EXPECT_EQ(c.n_kept(), p.n_free() - c.n_condensed());
    EXPECT_EQ(c.S_c().nonZeros(), kept_block_nonzeros(S, c));  // no fill

    std::vector<int> v, b;
    for (int i = 0; i < p.n_free(); ++i) (c.condenses(i) ? b : v).push_back(i);
    const Eigen::MatrixXd D(S);
    const Eigen::MatrixXd Svv = D(v, v), Svb = D(v, b), Sbb = D(b, b);
    const Eigen::MatrixXd schur = Svv - Svb * Sbb.ldlt().solve(Svb.transpose());
    // (the elimination cancels entries of size max |S| down to those of S_c: round-off
    // relative to S)
    EXPECT_LE((Eigen::MatrixXd(c.S_c()) - schur).cwiseAbs().maxCoeff(), 1e-14 * D.cwiseAbs().maxCoeff());
    std::cout << "dim " << mesh.dim << ": |S_c - Schur| = " << (Eigen::MatrixXd(c.S_c()) - schur).cwiseAbs().maxCoeff() << ", max |S| = " << D.cwiseAbs().maxCoeff() << "\n";
  }
}

// A time loop of the elastic body onto the inclined plane, with and without the block
// condensation (midpoint and backward Euler, direct solves): the same states to
// round-off, as for the membrane above (measured: see the output).
TEST(Condensation, ElasticTimeLoopsAgreeWithAndWithoutTheBlocks) {
  const Mesh mesh = unit_square_mesh(6);
  const ConstrainedProblem p = elastic_body(mesh);
  for (const std::string scheme : {"midpoint", "backward_euler"}) {
    QPOptions direct = cdyn::testing::tight();
    direct.pdas_cg_iterations = 0;
    PDASSolver s1(direct), s2(direct);
    SchemeParameters with, without;
    without.condense = false;
    const double dt = 0.02;
    auto t1 = make_time_scheme(scheme, p, s1, dt, with);
    auto t2 = make_time_scheme(scheme, p, s2, dt, without);
    State a;
    a.U = Eigen::VectorXd::Zero(p.n_free());
    a.V = p.mass->velocity(Eigen::VectorXd::Constant(p.n_free(), -0.1));  // towards the plane
    State b = a;
    double du = 0, dv = 0;
    int max_active = 0;
    for (int k = 0; k < 50; ++k) {  // contact after ≈ 0.1 / 0.1 / dt = 5 steps
      const StepStats st = t1->step(a);
      t2->step(b);
      max_active = std::max(max_active, st.active);
      du = std::max(du, (a.U - b.U).lpNorm<Eigen::Infinity>() / b.U.lpNorm<Eigen::Infinity>());
      dv = std::max(dv, (a.V - b.V).lpNorm<Eigen::Infinity>() / std::max(b.V.lpNorm<Eigen::Infinity>(), 1e-3));
    }
    std::cout << scheme << ": max |dU|/|U| = " << du << ", |dV|/|V| = " << dv << ", active up to " << max_active
              << "\n";
    EXPECT_GT(max_active, 0) << scheme;
    EXPECT_LE(du, 1e-10) << scheme;
    EXPECT_LE(dv, 1e-10) << scheme;
  }
}
