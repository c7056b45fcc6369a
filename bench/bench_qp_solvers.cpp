// bench_qp_solvers.cpp — the four step solvers (kernel/cdyn/qp.hpp) on the static membrane
// obstacle problem (P1 on square(n,n), f = −0.6, u = 0.02 on the boundary, u ≥ 0 at the
// vertices; the problem of tests/unit/test_qp_obstacle.cpp), n = 20 … 320.
//
//   cold/<solver>/n     a fresh solver object per solve: everything included (CHOLMOD
//                       analysis and factorizations for pdas, MUMPS for ipopt), from X = 0
//                       (pdas: from the unconstrained solution).  pgs uses the SOR optimum
//                       ω = 2/(1 + sin(π/n)) of the 5-point Laplacian.
//   pdas_warm/n         the same solver object again, warm-started from the solution: the
//                       floor of a time step (one forward/back solve with the kept factor).
//   pdas_sequence/n/limit  a "time loop" of 16 loads f_k = −0.6 (1 + 0.2 sin(2πk/16)),
//                       each solve warm-started from the previous one, S unchanged: the
//                       active set moves a little each step.  limit = pdas_update_limit
//                       (0: refactorize at every active-set change; otherwise CHOLMOD
//                       row updates for changes up to that many unknowns).  Time per step.
//
// Counters: dofs, iterations (pdas: linear solves; pgs: sweeps; ipopt: IP iterations;
// nlopt: products with S), kkt (the common residual), active.
//
// Run (Release build):
//   build-qp/bench/bench_qp_solvers --benchmark_counters_tabular=true
// pgs and nlopt are registered up to n = 160 only (beyond, one solve takes more than a
// few seconds; docs/performance.md); set CDYN_BENCH_ALL=1 to register them up to 320.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>

#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/fe/fe_space.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/qp/step_solver.hpp"
#ifdef CDYN_WITH_IPOPT
#include "cdyn/qp/ipopt.hpp"
#endif
#include "cdyn/qp/pdas/pdas.hpp"

namespace {

using Eigen::VectorXd;

struct Obstacle {
  cdyn::Mesh mesh;
  std::unique_ptr<cdyn::FESpace> W;
  cdyn::BoundQP qp;
  VectorXd load_part, lift_part;  // r = s · L_f − (A U_D)_f for a load f = s · (−0.6)

  explicit Obstacle(int n) : mesh(cdyn::unit_square_mesh(n)) {
    W = std::make_unique<cdyn::FESpace>(mesh, cdyn::Element::P1);
    const cdyn::SparseMatrix A = cdyn::assemble_laplace(*W);
    const VectorXd L = cdyn::assemble_load(*W, [](double, double, double) { return -0.6; });
    std::vector<int> parts;
    for (const char* p : {"bottom", "right", "top", "left"}) parts.push_back(mesh.part_index(p));
    const cdyn::DirichletLift lift(*W, parts);
    const VectorXd UD = lift.lifting(*W, {[](double, double, double) { return 0.02; }});
    qp.S = lift.restrict(A);
    qp.S.makeCompressed();
    load_part = lift.restrict(L);
    lift_part = lift.restrict(VectorXd(A * UD));
    qp.r = load_part - lift_part;
    qp.lower = VectorXd::Zero(qp.r.size());
    qp.upper = VectorXd::Constant(qp.r.size(), std::numeric_limits<double>::infinity());
  }
};

const Obstacle& obstacle(int n) {
  static std::map<int, std::unique_ptr<Obstacle>> cache;
  auto& p = cache[n];
  if (!p) p = std::make_unique<Obstacle>(n);
  return *p;
}

cdyn::QPOptions options_for(int n) {
  cdyn::QPOptions opt;
  opt.pgs_omega = 2.0 / (1.0 + std::sin(M_PI / n));
  return opt;
}

void report(benchmark::State& state, const cdyn::BoundQP& qp, const cdyn::QPResult& res) {
  state.counters["dofs"] = qp.size();
  state.counters["iterations"] = res.iterations;
  state.counters["kkt"] = res.kkt_residual;
  state.counters["active"] = static_cast<double>(res.active.size());
}

void cold(benchmark::State& state, const std::string& name) {
  const int n = static_cast<int>(state.range(0));
  const Obstacle& ob = obstacle(n);
  cdyn::QPResult res;
#ifdef CDYN_WITH_IPOPT
  cdyn::IpoptSolver::Statistics ipopt;
#endif
  for (auto _ : state) {
    auto solver = cdyn::make_step_solver(name, options_for(n));
    res = solver->solve(ob.qp);
    benchmark::DoNotOptimize(res.X.data());
#ifdef CDYN_WITH_IPOPT
    if (auto* ip = dynamic_cast<cdyn::IpoptSolver*>(solver.get())) ipopt = ip->last();
#endif
  }
  report(state, ob.qp, res);
#ifdef CDYN_WITH_IPOPT
  if (name == "ipopt") {  // what Ipopt reached alone, and the crossover's PDAS solves
    state.counters["ipopt_kkt"] = ipopt.ipopt_kkt_residual;
    state.counters["crossover"] = ipopt.crossover_solves;
  }
#endif
}

void pdas_warm(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Obstacle& ob = obstacle(n);
  cdyn::PDASSolver pdas(options_for(n));
  const cdyn::QPResult first = pdas.solve(ob.qp);
  cdyn::QPResult res;
  for (auto _ : state) {
    res = pdas.solve(ob.qp, &first);
    benchmark::DoNotOptimize(res.X.data());
  }
  report(state, ob.qp, res);
}

void pdas_sequence(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Obstacle& ob = obstacle(n);
  cdyn::QPOptions opt = options_for(n);
  opt.pdas_update_limit = static_cast<int>(state.range(1));
  cdyn::PDASSolver pdas(opt);
  constexpr int K = 16;
  std::vector<cdyn::BoundQP> steps(K, ob.qp);
  for (int k = 0; k < K; ++k) steps[k].r = (1.0 + 0.2 * std::sin(2 * M_PI * k / K)) * ob.load_part - ob.lift_part;
  cdyn::QPResult res = pdas.solve(steps[K - 1]);
  const auto before = pdas.counters();
  int k = 0, total_iterations = 0, solves = 0;
  for (auto _ : state) {
    res = pdas.solve(steps[k], &res);
    total_iterations += res.iterations;
    ++solves;
    k = (k + 1) % K;
  }
  report(state, ob.qp, res);
  state.counters["iterations"] = static_cast<double>(total_iterations) / solves;
  state.counters["factorizations"] =
      static_cast<double>(pdas.counters().factorizations - before.factorizations) / solves;
  state.counters["row_updates"] = static_cast<double>(pdas.counters().row_updates - before.row_updates) / solves;
}

void register_all() {
  const bool all = std::getenv("CDYN_BENCH_ALL") != nullptr;
  const std::vector<int> sizes = {20, 40, 80, 160, 320};
  for (const std::string& name : cdyn::step_solver_names()) {  // the solvers this build has
    const std::string label = std::string("cold/").append(name);
    auto* b = benchmark::RegisterBenchmark(label.c_str(), cold, name)->Unit(benchmark::kMillisecond);
    for (int n : sizes)
      if (all || name == "pdas" || name == "ipopt" || n <= 160) b->Arg(n);
    b->MinTime(0.5);
  }
  auto* w = benchmark::RegisterBenchmark("pdas_warm", pdas_warm)->Unit(benchmark::kMillisecond);
  for (int n : sizes) w->Arg(n);
  // one full cycle of the 16 loads per measurement (the mean over a cycle is what matters)
  auto* s = benchmark::RegisterBenchmark("pdas_sequence", pdas_sequence)->Unit(benchmark::kMillisecond)->Iterations(16);
  for (int n : {80, 160, 320})
    for (int limit : {0, 100, 300, 1000, -1}) s->Args({n, limit});
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
