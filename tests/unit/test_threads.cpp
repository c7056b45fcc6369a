// test_threads.cpp — results that do not depend on the number of threads of the kernel's
// loops, bit for bit (linalg/parallel.hpp, linalg/threads.hpp): the products and sums,
// CG, and whole time loops through an impact (P1+/P0 midpoint, P1/P1 backward Euler), on
// one thread and on two.  "The same" means equal bit for bit, not to a tolerance: the
// parallel loops are written so that every entry and every sum is computed in one order
// whatever the thread count, and a loop that broke that rule would show here as a
// difference of round-off.  The BLAS under CHOLMOD is kept on one thread there; on two,
// its threaded factorization changes the round-off of the factor, and the last test
// bounds what that does to a time loop.
//
// The sizes are chosen above the threshold at which the loops go parallel
// (kParallelWork), so that the two-thread runs do run on two threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/cell_coefficient.hpp"
#include "cdyn/mesh/mesh.hpp"

#include "cdyn/linalg/masked_cg.hpp"
#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/linalg/threads.hpp"
#include "cdyn/qp/pdas/pdas.hpp"
#include "cdyn/problems/scalar_wave.hpp"
#include "cdyn/schemes/time_scheme.hpp"

namespace {

using cdyn::SparseMatrix;
using Eigen::VectorXd;

bool same_bits(const VectorXd& a, const VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Runs f() with the kernel's loops on `threads` threads and the BLAS on `blas`, then
// gives the process its environment's counts back.
template <class F>
auto on_threads(int threads, F f, int blas = 1) {
  cdyn::set_thread_count(threads);
  cdyn::set_blas_thread_count(blas);
  auto result = f();
  cdyn::set_thread_count(0);
  cdyn::set_blas_thread_count(0);
  return result;
}

VectorXd random_vector(int n, std::mt19937& gen) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = U(gen);
  return x;
}

// The 5-point Laplacian of an m × m grid plus a random positive diagonal: symmetric to the
// last bit (each coupling is set once for both triangles), positive definite.
SparseMatrix grid_matrix(int m, std::mt19937& gen) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  auto at = [m](int i, int j) { return i + m * j; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      t.emplace_back(at(i, j), at(i, j), 4.0 + U(gen));
      if (i + 1 < m) {
        const double c = -1.0 + 0.1 * U(gen);
        t.emplace_back(at(i, j), at(i + 1, j), c);
        t.emplace_back(at(i + 1, j), at(i, j), c);
      }
      if (j + 1 < m) {
        const double c = -1.0 + 0.1 * U(gen);
        t.emplace_back(at(i, j), at(i, j + 1), c);
        t.emplace_back(at(i, j + 1), at(i, j), c);
      }
    }
  SparseMatrix S(m * m, m * m);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

TEST(Threads, TheCountIsSetAndGivenBack) {
  const int environment = cdyn::thread_count();
  cdyn::set_thread_count(2);
#ifdef CDYN_WITH_OPENMP
  EXPECT_EQ(cdyn::thread_count(), 2);
#endif
  cdyn::set_thread_count(1);
  EXPECT_EQ(cdyn::thread_count(), 1);
  cdyn::set_thread_count(0);
  EXPECT_EQ(cdyn::thread_count(), environment);
  for (auto set : {cdyn::set_thread_count, cdyn::set_blas_thread_count}) {
    try {
      set(-1);
      FAIL() << "a negative thread count was accepted";
    } catch (const cdyn::InputError& e) {
      EXPECT_EQ(e.parameter(), "threads");
    }
  }
  // OpenBLAS (0: another BLAS, which has no count to set)
  const int blas = cdyn::blas_thread_count();
  if (blas > 0) {
    cdyn::set_blas_thread_count(1);
    EXPECT_EQ(cdyn::blas_thread_count(), 1);
    cdyn::set_blas_thread_count(0);
    EXPECT_EQ(cdyn::blas_thread_count(), blas);
  }
}

// The threads of this process (Linux: /proc/self/task).
int process_threads() {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

// CHOLMOD 3 asks for a team of 4 OpenMP threads in its supernodal factorization's loops
// over large supernodes, whatever OMP_NUM_THREADS says; SparseCholesky bounds them by the
// kernel's count (linalg/threads.hpp, within_thread_count).  The process's threads are
// counted around a factorization of a grid matrix with supernodes of more than 10⁴
// entries, the BLAS on one thread (OpenBLAS starts its own threads for its own count):
// on one thread no thread may be started (without the bound: 3, measured), on two one
// worker at most.
TEST(Threads, ALibrarysParallelRegionsTakeTheKernelsCount) {
#ifndef CDYN_WITH_OPENMP
  GTEST_SKIP() << "built without OpenMP";
#endif
  std::mt19937 gen(7);
  const SparseMatrix S = grid_matrix(200, gen);
  cdyn::SparseCholesky chol;
  chol.analyze(S);
  cdyn::set_blas_thread_count(1);
  cdyn::set_thread_count(1);
  const int before = process_threads();
  ASSERT_EQ(chol.factorize(S), -1);
  EXPECT_EQ(process_threads(), before);
  cdyn::set_thread_count(2);
  ASSERT_EQ(chol.factorize(S), -1);
  EXPECT_LE(process_threads(), before + 1);
  cdyn::set_thread_count(0);
  cdyn::set_blas_thread_count(0);
  // an exception thrown inside the bounded call reaches the caller
  EXPECT_THROW(cdyn::within_thread_count([] { throw cdyn::InputError("thrown inside"); }), cdyn::InputError);
}

// The products are gathers whose terms are added in Eigen's order (j increasing), so they
// equal Eigen's serial products bit for bit, on any number of threads; the dot product
// is the sum of the block sums in order.
TEST(Threads, ProductsAndSumsAreTheSameOnOneAndTwoThreads) {
  std::mt19937 gen(7);
  const SparseMatrix S = grid_matrix(150, gen);  // 22 500 unknowns, 112 000 entries
  ASSERT_GE(S.nonZeros(), cdyn::kParallelWork);
  const VectorXd x = random_vector(static_cast<int>(S.rows()), gen);
  const VectorXd Sx = S * x;
  for (int threads : {1, 2}) {
    EXPECT_TRUE(same_bits(on_threads(threads, [&] { return cdyn::symmetric_times(S, x); }), Sx)) << threads;
  }

  // a rectangular B (the first half of S's rows): B x from Bᵀ's columns, Bᵀ y from B's
  SparseMatrix B = S.topRows(S.rows() / 2);
  B.makeCompressed();
  const SparseMatrix Bt = cdyn::transposed(B);
  const VectorXd y = random_vector(static_cast<int>(B.rows()), gen);
  const VectorXd Bx = B * x, Bty = B.transpose() * y;
  for (int threads : {1, 2}) {
    EXPECT_TRUE(same_bits(on_threads(threads, [&] { return cdyn::transpose_times(Bt, x); }), Bx)) << threads;
    EXPECT_TRUE(same_bits(on_threads(threads, [&] { return cdyn::transpose_times(B, y); }), Bty)) << threads;
  }

  // xᵀz of 100 000 entries (98 blocks, the last one shorter): the block sums added in order
  const VectorXd a = random_vector(100000, gen), z = random_vector(100000, gen);
  double by_blocks = 0.0;
  for (int begin = 0; begin < a.size(); begin += cdyn::kBlock) {
    const int length = std::min<int>(cdyn::kBlock, static_cast<int>(a.size()) - begin);
    by_blocks += a.segment(begin, length).dot(z.segment(begin, length));
  }
  for (int threads : {1, 2}) {
    EXPECT_TRUE(same_bits(on_threads(threads, [&] { return cdyn::dot(a, z); }), by_blocks)) << threads;
  }
}

// The elasticity matrix (fe/assembly.cpp: the cells' local matrices by chunks of 4 096 on
// every thread, their entries added in cell order): the same matrix, bit for bit, as on
// one thread.  3D P1+ on the 10³ cube, 6 000 cells (two chunks), one material per cell.
TEST(Threads, TheElasticityAssemblyIsTheSameOnOneAndTwoThreads) {
  const cdyn::Mesh mesh = cdyn::unit_cube_mesh(10);
  const cdyn::FESpace W(mesh, cdyn::Element::P1Bubble, 3);
  std::vector<double> lambda(mesh.n_cells()), mu(mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) lambda[c] = 1.0 + 0.001 * (c % 7), mu[c] = 0.5 + 0.002 * (c % 5);
  auto assemble = [&] { return cdyn::assemble_elasticity(W, cdyn::CellCoefficient(lambda), cdyn::CellCoefficient(mu)); };
  const SparseMatrix A1 = on_threads(1, assemble), A2 = on_threads(2, assemble);
  ASSERT_GT(mesh.n_cells(), 4096);
  ASSERT_EQ(A1.nonZeros(), A2.nonZeros());
  EXPECT_EQ(std::memcmp(A1.outerIndexPtr(), A2.outerIndexPtr(), sizeof(int) * (A1.outerSize() + 1)), 0);
  EXPECT_EQ(std::memcmp(A1.innerIndexPtr(), A2.innerIndexPtr(), sizeof(int) * A1.nonZeros()), 0);
  EXPECT_EQ(std::memcmp(A1.valuePtr(), A2.valuePtr(), sizeof(double) * A1.nonZeros()), 0);
}

// CG with a held set (the products, the multicolour sweeps, the vector updates and the
// reductions of every iteration): the same iterates, hence the same solution and count.
TEST(Threads, ConjugateGradientsAreTheSameOnOneAndTwoThreads) {
  std::mt19937 gen(11);
  const SparseMatrix S = grid_matrix(150, gen);
  const int n = static_cast<int>(S.rows());
  std::vector<char> held(n, 0);
  for (int i = 0; i < n; i += 5) held[i] = 1;
  const VectorXd b = random_vector(n, gen);
  struct Run {
    VectorXd y, residual;
    cdyn::MaskedCGResult result;
  };
  auto solve = [&] {
    cdyn::MaskedCG cg(S);
    Run r;
    r.result = cg.solve(held, b, r.y, 1e-12, 500);
    r.residual = cg.residual();
    return r;
  };
  const Run one = on_threads(1, solve), two = on_threads(2, solve);
  ASSERT_TRUE(one.result.converged);
  EXPECT_GT(one.result.iterations, 5);  // enough iterations for a difference to build up
  EXPECT_EQ(one.result.iterations, two.result.iterations);
  EXPECT_TRUE(same_bits(one.result.scaled_residual, two.result.scaled_residual));
  EXPECT_TRUE(same_bits(one.y, two.y));
  EXPECT_TRUE(same_bits(one.residual, two.residual));
}

// A PDAS solve on a grid of 151 × 151 unknowns, a third of them fixed (lower = upper:
// held from the first iteration), the others free: the right-hand side of its reduced
// system is made by the scatter over the held columns cut into row ranges
// (qp/pdas/explicit_reduced_system.cpp; the steps below hold too few unknowns for the
// cut).  The fixed unknowns are every i ≡ 1 mod 3: a grid line of 151 ≢ 0 mod 3 puts
// free rows next to held columns of the neighbouring range, across and down the grid.
// The same solution on one, two and three threads, to the tolerance: a row updated by
// two ranges, or a held column a range does not walk, changes X's bits.
TEST(Threads, PdasWithAThirdOfTheUnknownsHeldIsTheSameOnOneTwoAndThreeThreads) {
  std::mt19937 gen(5);
  cdyn::BoundQP qp;
  qp.S = grid_matrix(151, gen);
  const int n = static_cast<int>(qp.S.rows());
  qp.r = random_vector(n, gen);
  const VectorXd fixed = random_vector(n, gen);
  qp.lower = VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
  qp.upper = VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (int i = 1; i < n; i += 3) qp.lower[i] = qp.upper[i] = fixed[i];
  auto solve = [&] {
    cdyn::QPOptions options;
    options.tol = 1e-12;
    cdyn::PDASSolver pdas(options);
    return pdas.solve(qp);
  };
  const cdyn::QPResult one = on_threads(1, solve), two = on_threads(2, solve), three = on_threads(3, solve);
  for (const cdyn::QPResult* result : {&one, &two, &three}) {
    ASSERT_TRUE(result->converged);
    EXPECT_LE(result->kkt_residual, 1e-12);
  }
  EXPECT_EQ(static_cast<int>(one.active.size()), n / 3);  // 7 600 held: the cut needs 4 000
  for (const cdyn::QPResult* result : {&two, &three}) {
    EXPECT_TRUE(same_bits(one.X, result->X));
    EXPECT_TRUE(same_bits(one.reaction, result->reaction));
  }
}

// Resting contact: most unknowns on the obstacle X ≥ 0, a free patch that moves from
// call to call (warm-started, as a time loop's steps).  The PDAS iterates then take the
// ways of a mostly held set — CG on the free rows alone, λ on the rows held at two
// iterates updated over the columns where X moved, by the factor or by CG — and must
// give the same bits on one, two and three threads.
TEST(Threads, PdasOnAMostlyHeldSetIsTheSameOnOneTwoAndThreeThreads) {
  std::mt19937 gen(7);
  const int m = 151;
  cdyn::BoundQP qp;
  qp.S = grid_matrix(m, gen);
  const int n = static_cast<int>(qp.S.rows());
  qp.lower = VectorXd::Zero(n);
  qp.upper = VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (const bool cg_always : {false, true}) {
    auto solve = [&] {
      cdyn::QPOptions options;
      options.tol = 1e-12;
      options.pdas_cg_always = cg_always;
      cdyn::PDASSolver pdas(options);
      std::vector<cdyn::QPResult> results;
      for (int call = 0; call < 3; ++call) {
        qp.r = VectorXd::Constant(n, -1.0);  // pressed onto the obstacle but for a 40 × 40 patch
        const int first = 30 + 4 * call;
        for (int j = first; j < first + 40; ++j) qp.r.segment(j * m + first, 40).setConstant(1.0);
        results.push_back(pdas.solve(qp, results.empty() ? nullptr : &results.back()));
      }
      return results;
    };
    const auto one = on_threads(1, solve), two = on_threads(2, solve), three = on_threads(3, solve);
    for (int call = 0; call < 3; ++call) {
      ASSERT_TRUE(one[call].converged);
      EXPECT_GT(static_cast<int>(one[call].active.size()), n * 9 / 10);  // most held
      for (const auto* other : {&two, &three}) {
        EXPECT_TRUE(same_bits(one[call].X, (*other)[call].X)) << cg_always << " " << call;
        EXPECT_TRUE(same_bits(one[call].reaction, (*other)[call].reaction)) << cg_always << " " << call;
      }
    }
  }
}

// The seed's membrane at n = 80 (6 241 unknowns after condensation), 300 steps of
// dt = 0.001 through the impact at t ≈ 0.258: steps solved by the factor and by CG, the
// full-step reconstruction (midpoint), the mass model's products.  Every step's
// state, reaction and counts agree.
struct Trajectory {
  std::vector<VectorXd> U, V, reaction;
  std::vector<int> iterations, active;
  long cg_solves = 0, factorizations = 0;
};

Trajectory run_membrane(const std::string& pair, const std::string& scheme_name) {
  const cdyn::Mesh mesh = cdyn::unit_square_mesh(80);
  cdyn::ScalarWaveData d;
  d.mass = cdyn::MassSpec::parse(pair);
  d.f = [](double, double, double) { return -0.6; };
  d.dirichlet_parts = {0, 1, 2, 3};
  d.dirichlet_value = [](double, double, double) { return 0.02; };
  d.obstacle_g = [](double, double, double) { return 0.0; };
  const cdyn::ConstrainedProblem p = cdyn::build_scalar_wave(mesh, d);
  cdyn::QPOptions options;
  options.tol = 1e-12;
  cdyn::PDASSolver solver(options);
  cdyn::SchemeParameters parameters;
  parameters.tol = options.tol;
  auto scheme = cdyn::make_time_scheme(scheme_name, p, solver, 1e-3, parameters);
  cdyn::State s;
  s.U = p.unknowns(p.W->interpolate([](double, double, double) { return 0.02; }));
  s.V = cdyn::initial_velocity(p, VectorXd::Zero(p.n_free()));
  Trajectory t;
  for (int k = 0; k < 300; ++k) {
    const cdyn::StepStats stats = scheme->step(s);
    t.U.push_back(s.U);
    t.V.push_back(s.V);
    t.reaction.push_back(s.reaction);
    t.iterations.push_back(stats.qp_iterations);
    t.active.push_back(stats.active);
  }
  t.cg_solves = solver.counters().cg_solves;
  t.factorizations = solver.counters().factorizations;
  return t;
}

void expect_same_trajectories(const std::string& pair, const std::string& scheme) {
  const Trajectory one = on_threads(1, [&] { return run_membrane(pair, scheme); });
  const Trajectory two = on_threads(2, [&] { return run_membrane(pair, scheme); });
  ASSERT_EQ(one.U.size(), 300u);
  ASSERT_GT(one.cg_solves, 0) << "the window should have steps solved by CG";
  ASSERT_GT(*std::max_element(one.active.begin(), one.active.end()), 0) << "no contact in 300 steps";
  EXPECT_EQ(one.cg_solves, two.cg_solves);
  EXPECT_EQ(one.factorizations, two.factorizations);
  for (std::size_t k = 0; k < one.U.size(); ++k) {
    SCOPED_TRACE("step " + std::to_string(k + 1));
    ASSERT_EQ(one.iterations[k], two.iterations[k]);
    ASSERT_EQ(one.active[k], two.active[k]);
    ASSERT_TRUE(same_bits(one.U[k], two.U[k]));
    ASSERT_TRUE(same_bits(one.V[k], two.V[k]));
    ASSERT_TRUE(same_bits(one.reaction[k], two.reaction[k]));
  }
}

TEST(Threads, MidpointStepsThroughAnImpactAreTheSameOnOneAndTwoThreads) {
  expect_same_trajectories("P1+/P0", "midpoint");
}

TEST(Threads, BackwardEulerStepsThroughAnImpactAreTheSameOnOneAndTwoThreads) {
  expect_same_trajectories("P1/P1", "backward_euler");
}

// The BLAS on two threads (OpenBLAS's threaded dpotrf and dgemv under CHOLMOD) changes
// the factor's round-off, by 1e-16 relative in a solve.  Through the impact that must stay
// a perturbation of the solves: the same iteration counts and active sets at every step,
// and states that agree to the accuracy the steps are solved to — solver.tol = 1e-12 of
// the solution's scale, which a CG solve may end anywhere within (measured: 8e-13 for
// P1+/P0 midpoint, 6e-14 for P1/P1 backward Euler, over the 300 steps); the test allows
// 1e-11.  (With another BLAS, which has no threads to set, the two runs are the same.)
void expect_round_off_apart(const std::string& pair, const std::string& scheme) {
  const Trajectory one = on_threads(1, [&] { return run_membrane(pair, scheme); }, 1);
  const Trajectory two = on_threads(1, [&] { return run_membrane(pair, scheme); }, 2);
  ASSERT_EQ(one.U.size(), 300u);
  EXPECT_EQ(one.cg_solves, two.cg_solves);
  EXPECT_EQ(one.factorizations, two.factorizations);
  double scale = 0.0, apart = 0.0;
  for (std::size_t k = 0; k < one.U.size(); ++k) {
    SCOPED_TRACE("step " + std::to_string(k + 1));
    ASSERT_EQ(one.iterations[k], two.iterations[k]);
    ASSERT_EQ(one.active[k], two.active[k]);
    scale = std::max(scale, one.U[k].lpNorm<Eigen::Infinity>());
    apart = std::max(apart, (one.U[k] - two.U[k]).lpNorm<Eigen::Infinity>());
  }
  EXPECT_LE(apart, 1e-11 * scale);
}

TEST(Threads, TheBlasOnTwoThreadsChangesTheStepsByRoundOff) {
  expect_round_off_apart("P1+/P0", "midpoint");
  expect_round_off_apart("P1/P1", "backward_euler");
}

}  // namespace
