// bench_condition12.cpp — condition (12) at any size (docs/performance.md, "Condition (12)
// at any size"): wall time and peak memory of β = σ_min(G Z) by the sparse method
// (wellposedness/condition12_sparse.hpp) on the seed's membrane, P1+/P0, u fixed on the
// whole boundary, the obstacle at every vertex (N_g = the interior vertices), for
// n = 40 … 577: N_W = (n − 1)² + 2n² free dofs, 4 721 … 997 634 (n = 320: 306 561).
//
// One benchmark per n, one iteration each (a run at 1M dofs is a minute), in increasing
// n so that the process's peak resident set (VmHWM) after a run is that run's peak.  The
// time is condition12(B, G) alone; the assembly of B and G is the counter asm_s.
// Counters: N_W, N_H, N_g, beta, fact (Cholesky factorizations of the shifted Gram
// matrix), solves (with them), peak_MB.  After the table: the exponents p of time ∝ N_W^p
// and peak memory ∝ N_W^p, least squares over the sizes and between consecutive ones.
// Targets (the performance issue): 300k dofs in under a minute, 1M in under five.
//
// Run (Release build; one thread for OpenBLAS, as scripts/bench.sh does):
//   OPENBLAS_NUM_THREADS=1 build/bench/bench_condition12 --benchmark_counters_tabular=true
// CDYN_BENCH_N="40,80,160" chooses the sizes (default 40,80,160,320,400,577).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cdyn/mass/mass_model.hpp"
#include "cdyn/wellposedness/condition12.hpp"

namespace {

using namespace cdyn;

std::vector<int> sizes() {
  const char* s = std::getenv("CDYN_BENCH_N");
  std::vector<int> n;
  std::stringstream in(s ? s : "40,80,160,320,400,577");
  for (std::string item; std::getline(in, item, ',');) n.push_back(std::stoi(item));
  return n;
}

// Peak resident set of this process so far, MB.
double peak_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

struct Measured {
  int n_W;
  double seconds, peak;
};
std::vector<Measured> g_measured;

void condition12_membrane(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh mesh = unit_square_mesh(n);
    const FESpace W(mesh, Element::P1Bubble);
    const DirichletLift bc(W, {mesh.part_index("bottom"), mesh.part_index("right"), mesh.part_index("top"),
                               mesh.part_index("left")});
    std::vector<int> vertices(mesh.n_vertices());
    for (int v = 0; v < mesh.n_vertices(); ++v) vertices[v] = v;
    const SparseMatrix G = vertex_constraint_matrix(W, bc, vertices);
    const SparseMatrix B = mixed_blocks(W, bc, Element::P0, 1.0).B;
    const auto t1 = std::chrono::steady_clock::now();
    const WellPosedness r = condition12(B, G);
    const auto t2 = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(t2 - t1).count();
    state.SetIterationTime(seconds);
    state.counters["N_W"] = r.n_W;
    state.counters["N_H"] = r.n_H;
    state.counters["N_g"] = r.n_g;
    state.counters["beta"] = r.beta;
    state.counters["fact"] = r.factorizations;
    state.counters["solves"] = r.solves;
    state.counters["asm_s"] = std::chrono::duration<double>(t1 - t0).count();
    state.counters["peak_MB"] = peak_mb();
    g_measured.push_back({r.n_W, seconds, peak_mb()});
  }
}

// Exponent p of y ∝ N^p: least squares in log–log over all sizes.
double exponent(const std::vector<Measured>& m, double Measured::*y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& r : m) {
    const double x = std::log(r.n_W), v = std::log(r.*y);
    sx += x, sy += v, sxx += x * x, sxy += x * v;
  }
  const double k = static_cast<double>(m.size());
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

}  // namespace

int main(int argc, char** argv) {
  for (int n : sizes())
    benchmark::RegisterBenchmark("condition12/P1+/P0", condition12_membrane)
        ->Arg(n)
        ->ArgName("n")
        ->Iterations(1)
        ->UseManualTime()
        ->Unit(benchmark::kSecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  if (g_measured.size() >= 2) {
    std::printf("\nexponents (time ∝ N_W^p, peak memory ∝ N_W^p): least squares p_time %.2f, p_memory %.2f\n",
                exponent(g_measured, &Measured::seconds), exponent(g_measured, &Measured::peak));
    for (size_t k = 1; k < g_measured.size(); ++k) {
      const auto &a = g_measured[k - 1], &b = g_measured[k];
      const double dn = std::log(static_cast<double>(b.n_W) / a.n_W);
      std::printf("  N_W %7d -> %7d: p_time %.2f, p_memory %.2f\n", a.n_W, b.n_W, std::log(b.seconds / a.seconds) / dn,
                  std::log(b.peak / a.peak) / dn);
    }
  }
  benchmark::Shutdown();
  return 0;
}
