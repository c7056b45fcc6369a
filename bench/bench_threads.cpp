// bench_threads.cpp — what the second core gives (docs/performance.md, "Both cores"): the
// mean time of a step over the impact window of the seed's membrane (steps 241–270: the
// impact at step 257, where the active set jumps from 0 to thousands of vertices, and the
// chattering after it; bench_contact_step.cpp's window is 211–310, twice as long, which
// this benchmark's 8 runs a size cannot afford at n = 640), for P1+/P0 midpoint and P1/P1 backward Euler, n = 320 and 640, on one thread
// and on two (the kernel's loops, set_thread_count, and OpenBLAS under CHOLMOD,
// set_blas_thread_count: linalg/threads.hpp).
//
//   window/<pair>/<scheme>/threads:K/n:N
//
// The 239 steps before the window run once per case, untimed, with the loops on two
// threads and the BLAS on one (the same state whatever K: the loops' results do not
// depend on their thread count, the BLAS's do, by round-off); their state and scheme
// memory (schemes/scheme_memory.hpp) are kept.  Each iteration builds a fresh scheme and
// solver, restores that memory, takes step 240 untimed (it rebuilds the solver's factor,
// as the steps before did in a run) and times the window on K threads (manual time:
// seconds per step).  One run of each case unless --benchmark_repetitions says more;
// scripts/bench.sh interleaves the cases at random (--benchmark_enable_random_interleaving=true)
// so that one and two threads see the same machine.  Counters per step: qp_ms (the solver's share), cg_ms, solve_ms (forward/back
// solves with the factor), fact_ms (numeric factorizations); unknowns, the free dofs.
//
// The two cores need not be equally fast: on the 2-core virtual machine of docs/
// performance.md the second runs this window 1.2–2.2 times slower than the first (a
// busy neighbour on the host; no process of ours on it), and an unpinned one-thread run
// landed on either, which made its speed-up 1.1–1.8 from run to run.  So the process is
// kept on its first two CPUs, a one-thread case runs pinned to each in turn
// (threads:1/cpu:K), and the two-thread case on both.
//
// After the table: the speed-up of each case over one thread on the faster core and on
// the slower (target ≥ 1.6), the best two such cores could give, 1 + t_fast / t_slow (the
// work split in proportion to their speeds), and how far apart the states after the
// window are, max |U₁ − U₂| / max |U₁|: 0 but for the BLAS's round-off (its threaded
// factorization and solve, linalg/threads.hpp).
// Run (Release build, an idle machine; about 2 minutes, 4 with --benchmark_repetitions=2):
//   build/bench/bench_threads --benchmark_counters_tabular=true --benchmark_enable_random_interleaving=true
// CDYN_BENCH_SIZES=80,160 runs other sizes (the window is the same: the impact time does not
// depend on the mesh); CDYN_BENCH_LINEAR=cg solves the step QPs by CG alone (solver.linear =
// "cg": no factor, so no triangular solve left on one core).
#include <benchmark/benchmark.h>

#include <malloc.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cdyn/linalg/threads.hpp"
#include "cdyn/qp/pdas/pdas.hpp"
#include "seed_membrane.hpp"

namespace {

using namespace cdyn;

constexpr int kBefore = 240, kWindow = 30;
constexpr double kDt = 1e-3;

struct Method {
  std::string pair, scheme;
};
const Method kMethods[] = {{"P1+/P0", "midpoint"}, {"P1/P1", "backward_euler"}};

bool cg_only() {
  const char* s = std::getenv("CDYN_BENCH_LINEAR");
  return s && std::string(s) == "cg";
}

std::vector<int> sizes() {
  const char* s = std::getenv("CDYN_BENCH_SIZES");
  std::vector<int> out;
  std::stringstream list(s ? s : "320,640");
  for (std::string n; std::getline(list, n, ',');) out.push_back(std::stoi(n));
  return out;
}

const bench::SeedMembrane& membrane(int n, const std::string& pair) {
  static std::map<std::pair<int, std::string>, std::unique_ptr<bench::SeedMembrane>> cache;
  auto& m = cache[{n, pair}];
  if (!m) m = std::make_unique<bench::SeedMembrane>(n, true, pair);
  return *m;
}

// The state and scheme memory after the steps before the window (one untimed run per
// case, on two threads for the loops and one for the BLAS).
struct BeforeWindow {
  State s;
  SchemeMemory memory;
};
const BeforeWindow& before_window(const bench::SeedMembrane& m, const Method& method, const QPOptions& opt,
                                  const SchemeParameters& par) {
  static std::map<std::pair<const void*, std::string>, BeforeWindow> cache;
  auto [it, fresh] = cache.try_emplace({&m, method.scheme});
  if (fresh) {
    PDASSolver solver(opt);
    auto scheme = make_time_scheme(method.scheme, m.p, solver, kDt, par);
    it->second.s = m.initial();
    set_thread_count(2);
    set_blas_thread_count(1);
    for (int k = 0; k < kBefore - 1; ++k) scheme->step(it->second.s);
    it->second.memory = scheme->memory();
  }
  return it->second;
}

struct Totals {
  double seconds = 0.0, steps = 0.0;
  Eigen::VectorXd last_U;  // the state after the window, to compare across thread counts
};
// case name → where it ran (a CPU for one thread, kBoth for two) → totals
constexpr int kBoth = -1;
std::map<std::string, std::map<int, Totals>> g_totals;

// The first two CPUs this process may run on (the cores of the comparison).
std::vector<int> g_cpus;
cpu_set_t cpus_of(const std::vector<int>& list) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int c : list) CPU_SET(c, &set);
  return set;
}
// Stops the benchmark: a case not run where its name says would be timed on another core.
[[noreturn]] void affinity_failed(const char* call) {
  std::perror(call);
  std::exit(2);
}
// The calling thread on `list` only (sched_setaffinity with pid 0: this thread).
void run_on(const std::vector<int>& list) {
  const cpu_set_t set = cpus_of(list);
  if (sched_setaffinity(0, sizeof set, &set) != 0) affinity_failed("sched_setaffinity");
}

// cpu: the CPU a one-thread case runs on; kBoth for the two-thread case.
void window(benchmark::State& state, const Method& method, int threads, int cpu) {
  const int n = static_cast<int>(state.range(0));
  const bench::SeedMembrane& m = membrane(n, method.pair);
  QPOptions opt;
  opt.tol = 1e-12;  // the scene's solver.tol
  opt.pdas_cg_only = cg_only();
  SchemeParameters par;
  par.tol = opt.tol;
  double qp = 0, cg_s = 0, solve_s = 0, factor_s = 0;
  Totals& totals = g_totals[method.pair + " " + method.scheme + " n=" + std::to_string(n)][cpu];
  const BeforeWindow& before = before_window(m, method, opt, par);
  for (auto _ : state) {
    PDASSolver solver(opt);
    auto scheme = make_time_scheme(method.scheme, m.p, solver, kDt, par);
    State s = before.s;
    scheme->restore(before.memory);
    set_thread_count(2);
    set_blas_thread_count(1);
    scheme->step(s);  // step 240
    set_thread_count(threads);
    set_blas_thread_count(threads);
    if (cpu != kBoth) run_on({cpu});
    const PDASSolver::Counters c0 = solver.counters();
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kWindow; ++k) qp += scheme->step(s).qp_seconds;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run_on(g_cpus);
    set_thread_count(0);
    set_blas_thread_count(0);
    state.SetIterationTime(seconds / kWindow);
    totals.seconds += seconds;
    totals.steps += kWindow;
    totals.last_U = s.U;
    cg_s += solver.counters().cg_s - c0.cg_s;
    solve_s += solver.counters().solve_s - c0.solve_s;
    factor_s += solver.counters().factorization_s - c0.factorization_s;
  }
  const double steps = static_cast<double>(state.iterations()) * kWindow;
  state.counters["unknowns"] = static_cast<double>(m.p.n_free());
  state.counters["qp_ms"] = 1e3 * qp / steps;
  state.counters["cg_ms"] = 1e3 * cg_s / steps;
  state.counters["solve_ms"] = 1e3 * solve_s / steps;
  state.counters["fact_ms"] = 1e3 * factor_s / steps;
}

void register_all() {
  for (int n : sizes())
    for (const Method& method : kMethods)
      for (int cpu : [] {
             std::vector<int> where = g_cpus;
             where.push_back(kBoth);
             return where;
           }()) {
        const int threads = cpu == kBoth ? 2 : 1;
        const std::string name = "window/" + method.pair + "/" + method.scheme + "/threads:" + std::to_string(threads) +
                                 (cpu == kBoth ? "" : "/cpu:" + std::to_string(cpu));
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) { window(s, method, threads, cpu); })
            ->Arg(n)
            ->ArgName("n")
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(1);
      }
}

// The process on its first two allowed CPUs, before any thread is started: threads inherit
// it.  (The OpenMP team is made on two threads outside the pinned windows, by the untimed
// steps before them.)
void keep_to_two_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) affinity_failed("sched_getaffinity");
  for (int c = 0; c < CPU_SETSIZE && g_cpus.size() < 2; ++c)
    if (CPU_ISSET(c, &set)) g_cpus.push_back(c);
  run_on(g_cpus);
}


}  // namespace

int main(int argc, char** argv) {
  // freed memory kept in the heap, as the cdyn program does (apps/cdyn/main.cpp), so that
  // the steps timed here allocate as a run's steps do
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
  keep_to_two_cpus();
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  std::printf("\nmean step over the window and the repetitions, one thread on each CPU and two threads on both;\n"
              "speed-up = 1 thread on the faster CPU (and on the slower) / 2 threads (target >= 1.6); bound: the best\n"
              "two cores of these speeds give, 1 + t_fast / t_slow\n");
  for (auto& [name, by_cpu] : g_totals) {
    if (!by_cpu.count(kBoth) || by_cpu.size() < 2) continue;
    const Totals& two = by_cpu[kBoth];
    const double t2 = two.seconds / two.steps;
    double fast = 0.0, slow = 0.0, apart = 0.0;
    for (auto& [cpu, one] : by_cpu) {
      if (cpu == kBoth) continue;
      const double t1 = one.seconds / one.steps;
      fast = fast > 0.0 ? std::min(fast, t1) : t1;
      slow = std::max(slow, t1);
      apart = std::max(apart, (one.last_U - two.last_U).lpNorm<Eigen::Infinity>() / one.last_U.lpNorm<Eigen::Infinity>());
    }
    std::printf("%-32s 1 thread %8.3f / %8.3f ms   2 threads %8.3f ms   speed-up %.2f / %.2f   bound %.2f   states apart %.1e\n",
                name.c_str(), 1e3 * fast, 1e3 * slow, 1e3 * t2, fast / t2, slow / t2, 1.0 + fast / slow, apart);
  }
  benchmark::Shutdown();
  return 0;
}
