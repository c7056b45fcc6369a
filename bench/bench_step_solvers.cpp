// bench_step_solvers.cpp — the solver table of docs/performance.md (d): pdas, pgs, ipopt and nlopt on the
// SAME time steps.  The seed's membrane (data/scenes/membrane.toml: P1+/P0, midpoint,
// dt = 0.001, bubbles condensed) is run with pdas through steps 1–300 and the step QPs
// of steps 241–300 (the impact at t ≈ 0.258 and the contact after it) are recorded: S_c
// (fixed), the bounds, and each step's r.  Each solver then solves that sequence, each QP
// warm-started from its own previous result (as in a time loop), at the scene's
// tolerance kkt_residual ≤ 1e-12 (qp/bound_qp.hpp: the same measure for every solver).
//
// Counters: ms/step (the time column, manual), iters (mean per step: pdas linear solves,
// pgs sweeps, ipopt interior-point iterations, nlopt evaluations), kkt_max (largest
// residual reached), failed (steps that did not reach the tolerance), unknowns (of the
// condensed QP).  pgs uses ω = 1 (S_c is not the 5-point Laplacian of bench_qp_solvers).
//
// Run (Release build):  build-perf/bench/bench_step_solvers --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>

#include "cdyn/qp/pdas/pdas.hpp"
#include "seed_membrane.hpp"

namespace {

using namespace cdyn;

constexpr int kFirst = 241, kLast = 300;

// Delegates to pdas and keeps a copy of the QPs of the recorded steps.
class Recorder final : public StepSolver {
 public:
  std::string name() const override { return "recorder"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm) override {
    ++step_;
    if (step_ >= kFirst && step_ <= kLast) qps.push_back(qp);
    return pdas_.solve(qp, warm);
  }
  std::vector<BoundQP> qps;

 private:
  PDASSolver pdas_;
  int step_ = 0;
};

const std::vector<BoundQP>& steps(int n) {
  static std::map<int, std::vector<BoundQP>> cache;
  auto& q = cache[n];
  if (!q.empty()) return q;
  const bench::SeedMembrane m(n, true);
  const ConstrainedProblem& p = m.p;
  Recorder rec;
  auto scheme = make_time_scheme("midpoint", p, rec, 1e-3);
  State s = m.initial();
  for (int k = 0; k < kLast; ++k) scheme->step(s);
  q = std::move(rec.qps);
  return q;
}

void sequence(benchmark::State& state, const std::string& solver_name) {
  const int n = static_cast<int>(state.range(0));
  const std::vector<BoundQP>& qps = steps(n);
  QPOptions opt;
  opt.tol = 1e-12;
  opt.throw_on_failure = false;
  if (solver_name == "pgs") opt.max_iterations = 20000;
  double iters = 0, kkt_max = 0, failed = 0, count = 0;
  for (auto _ : state) {
    auto solver = make_step_solver(solver_name, opt);
    QPResult last;
    bool has_last = false;
    const auto start = std::chrono::steady_clock::now();
    for (const BoundQP& qp : qps) {
      last = solver->solve(qp, has_last ? &last : nullptr);
      has_last = true;
      iters += last.iterations;
      kkt_max = std::max(kkt_max, last.kkt_residual);
      failed += last.converged ? 0 : 1;
      ++count;
    }
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                           static_cast<double>(qps.size()));
  }
  state.counters["unknowns"] = qps.front().size();
  state.counters["iters"] = iters / count;
  state.counters["kkt_max"] = kkt_max;
  state.counters["failed"] = failed / (count / static_cast<double>(qps.size()));
}

void register_all() {
  for (const std::string name : {"pdas", "pgs", "ipopt", "nlopt"})
    benchmark::RegisterBenchmark(("steps/" + name).c_str(), [=](benchmark::State& s) { sequence(s, name); })
        ->Arg(40)
        ->Arg(80)
        ->ArgName("n")
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
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
