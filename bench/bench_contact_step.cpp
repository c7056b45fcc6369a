// bench_contact_step.cpp — the cost of contact in a time step (docs/performance.md (a)):
// the seed's membrane (P1+/P0, midpoint with the constraint on the half step,
// dt = 0.001, f = −0.6, u = 0.02 on the boundary and at t = 0, u ≥ 0 at the vertices:
// data/scenes/membrane.toml) at n = 160, over the 100 steps 211–310, which contain the
// impact (free fall 0.02 − 0.3 t² reaches the obstacle at t ≈ 0.258; the active set
// grows to ≈ 7 900 vertices, then chatters by hundreds of vertices per step).
//
//   window/contact/condense:c/cg:k   pdas steps on the constrained problem
//   window/linear/condense:c/cg:k    the same scheme with obstacle.enabled = false: the
//                                   same S, no bounds, so every step is one forward/back
//                                   solve with the kept factor (plus the right-hand side
//                                   and the update, as in the contact step)
// condense = 1: the bubbles eliminated (schemes/step_qp_scheme.hpp, qp/condensation.hpp), 0: the full
// 76 481-unknown QP; cg = QPOptions::pdas_cg_iterations (0: active-set changes only by
// CHOLMOD row updates or refactorization, qp/pdas/pdas.hpp).  The 209 steps before the
// window run once per case, untimed, and their state and scheme memory
// (schemes/scheme_memory.hpp: the checkpoint's mechanism, a restart bit for bit) are
// kept; each iteration builds a fresh scheme and solver, restores that memory, takes
// step 210 untimed (it builds the solver's factor, as the steps before did in a run) and
// times the window (manual time: seconds per step); 5 repetitions of each case, which scripts/bench.sh
// interleaves at random (--benchmark_enable_random_interleaving=true) so that the linear
// and the contact windows see the same machine: on this VM a window's time drifts by up
// to 25 % between runs minutes apart, and the ratio must not inherit that.
// Counters per step: qp_ms (the solver's share), iters (pdas linear solves), factor
// (numeric factorizations), rowupd (CHOLMOD row updates), cg (CG solves), cg_it/cg (CG
// iterations per CG solve), max_active; unknowns counts the free dofs before condensation;
// fact_ms, upd_ms, solve_ms, cg_ms: the solver's milliseconds per step in factorizations,
// row updates, forward/back solves and CG (PDASSolver::Counters): where the time goes.
//
// After the table it prints the ratios contact/linear (target ≤ 1.5, docs/performance.md (a)).
// Run (Release build):
//   build-perf/bench/bench_contact_step --benchmark_counters_tabular=true
// CDYN_BENCH_N=80 runs a smaller mesh (the window is the same: the impact time does not
// depend on the mesh).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "cdyn/qp/pdas/pdas.hpp"
#include "seed_membrane.hpp"

namespace {

using namespace cdyn;

constexpr int kBefore = 210, kWindow = 100;
constexpr double kDt = 1e-3;

int mesh_n() {
  const char* s = std::getenv("CDYN_BENCH_N");
  return s ? std::atoi(s) : 160;
}

using Membrane = bench::SeedMembrane;

const Membrane& membrane(int n, bool obstacle) {
  static std::map<std::pair<int, bool>, std::unique_ptr<Membrane>> cache;
  auto& m = cache[{n, obstacle}];
  if (!m) m = std::make_unique<Membrane>(n, obstacle);
  return *m;
}

std::map<std::string, std::pair<double, double>> g_window;  // name → (seconds, steps) over the repetitions

// The state and scheme memory after the steps before the window (one untimed run per case).
struct BeforeWindow {
  State s;
  SchemeMemory memory;
};
const BeforeWindow& before_window(const Membrane& m, const QPOptions& opt, const SchemeParameters& par) {
  static std::map<std::tuple<const void*, bool, int>, BeforeWindow> cache;
  auto [it, fresh] = cache.try_emplace({&m, par.condense, opt.pdas_cg_iterations});
  if (fresh) {
    PDASSolver solver(opt);
    auto scheme = make_time_scheme("midpoint", m.p, solver, kDt, par);
    it->second.s = m.initial();
    for (int k = 0; k < kBefore - 1; ++k) scheme->step(it->second.s);
    it->second.memory = scheme->memory();
  }
  return it->second;
}

void window(benchmark::State& state, bool obstacle, bool condense, int cg_iterations) {
  const int n = static_cast<int>(state.range(0));
  const Membrane& m = membrane(n, obstacle);
  QPOptions opt;
  opt.tol = 1e-12;  // the scene's solver.tol
  opt.pdas_cg_iterations = cg_iterations;
  double qp = 0, total = 0, iters = 0, factor = 0, rowupd = 0, cg = 0, cgit = 0;
  double factor_s = 0, rowupd_s = 0, solve_s = 0, cg_s = 0;
  int max_active = 0, runs = 0;
  SchemeParameters par;
  par.condense = condense;
  const BeforeWindow& before = before_window(m, opt, par);
  for (auto _ : state) {
    PDASSolver solver(opt);
    auto scheme = make_time_scheme("midpoint", m.p, solver, kDt, par);
    State s = before.s;
    scheme->restore(before.memory);
    scheme->step(s);  // step 210
    const PDASSolver::Counters c0 = solver.counters();
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kWindow; ++k) {
      const StepStats st = scheme->step(s);
      qp += st.qp_seconds;
      iters += st.qp_iterations;
      max_active = std::max(max_active, st.active);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds / kWindow);
    total += seconds;
    factor += solver.counters().factorizations - c0.factorizations;
    rowupd += solver.counters().row_updates - c0.row_updates;
    cg += solver.counters().cg_solves - c0.cg_solves;
    cgit += solver.counters().cg_iterations - c0.cg_iterations;
    factor_s += solver.counters().factorization_s - c0.factorization_s;
    rowupd_s += solver.counters().row_update_s - c0.row_update_s;
    solve_s += solver.counters().solve_s - c0.solve_s;
    cg_s += solver.counters().cg_s - c0.cg_s;
    ++runs;
  }
  const double steps = static_cast<double>(runs) * kWindow;
  state.counters["unknowns"] = static_cast<double>(m.p.n_free());
  state.counters["qp_ms"] = 1e3 * qp / steps;
  state.counters["iters"] = iters / steps;
  state.counters["factor"] = factor / steps;
  state.counters["rowupd"] = rowupd / steps;
  state.counters["max_active"] = max_active;
  state.counters["cg"] = cg / steps;
  state.counters["cg_it/cg"] = cg > 0 ? cgit / cg : 0.0;
  state.counters["fact_ms"] = 1e3 * factor_s / steps;
  state.counters["upd_ms"] = 1e3 * rowupd_s / steps;
  state.counters["solve_ms"] = 1e3 * solve_s / steps;
  state.counters["cg_ms"] = 1e3 * cg_s / steps;
  auto& acc = g_window[std::string(obstacle ? "contact" : "linear") + (condense ? "/condensed" : "/full") +
                       (obstacle && cg_iterations == 0 ? "/no-cg" : "")];
  acc.first += total;
  acc.second += steps;
}

void register_all() {
  const int n = mesh_n();
  const int cg_default = QPOptions{}.pdas_cg_iterations;
  struct Case {
    bool obstacle, condense;
    int cg;
  };
  for (const Case c : {Case{false, true, cg_default}, Case{true, true, cg_default}, Case{true, true, 0},
                       Case{false, false, cg_default}, Case{true, false, cg_default}}) {
    const std::string name = "window/" + std::string(c.obstacle ? "contact" : "linear") + "/condense:" +
                             (c.condense ? "1" : "0") + "/cg:" + std::to_string(c.cg);
    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) { window(s, c.obstacle, c.condense, c.cg); })
        ->Arg(n)
        ->ArgName("n")
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  auto at = [](const std::string& k) { return g_window.count(k) ? g_window[k].first / g_window[k].second : 0.0; };
  std::printf("\nmean step over the window and the repetitions (ms): ");
  for (const auto& [k, v] : g_window) std::printf("%s %.3f  ", k.c_str(), 1e3 * v.first / v.second);
  std::printf("\n");
  if (at("linear/condensed") > 0 && at("contact/condensed") > 0)
    std::printf("contact overhead, condensed: pdas step / linear step = %.2f (target <= 1.5)\n",
                at("contact/condensed") / at("linear/condensed"));
  if (at("linear/condensed") > 0 && at("contact/condensed/no-cg") > 0)
    std::printf("contact overhead, condensed, factor updates only (pdas_cg_iterations = 0): %.2f\n",
                at("contact/condensed/no-cg") / at("linear/condensed"));
  if (at("linear/full") > 0 && at("contact/full") > 0)
    std::printf("contact overhead, full QP:   pdas step / linear step = %.2f\n", at("contact/full") / at("linear/full"));
  if (at("linear/full") > 0 && at("linear/condensed") > 0)
    std::printf("condensation speed-up: linear %.2fx, contact %.2fx\n", at("linear/full") / at("linear/condensed"),
                at("contact/full") > 0 ? at("contact/full") / at("contact/condensed") : 0.0);
  benchmark::Shutdown();
  return 0;
}
