// bench_bandwidth.cpp — what a second core can give a memory-bound loop on this machine
// (docs/performance.md, "Both cores"): the ceiling of the two-thread speed-up of a step
// whose work is sparse products and vector sweeps that read their operands once.
//
//   triad/threads:K       a = b + s c over three arrays of 2²⁴ doubles (384 MB: out of
//                         every cache), the STREAM triad (McCalpin 1995), by OpenMP;
//   product/threads:K     y = S x with the kernel's threaded gather (linalg/parallel.hpp)
//                         for S the 9-point pattern of a 1100 × 1100 grid (1.21M rows,
//                         10.9M entries, about the condensed P1+/P0 step matrix at
//                         n = 640), the step's own kind of loop.
//
// Counters: GB/s (bytes read and written once, as STREAM counts them).  Run on an idle
// machine; the ratio of the two thread counts in one run is the figure:
//   build/bench/bench_bandwidth --benchmark_enable_random_interleaving=true
#include <benchmark/benchmark.h>

#include <vector>

#include "cdyn/base/sparse.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/linalg/threads.hpp"

namespace {

constexpr long kLength = 1L << 24;

void triad(benchmark::State& state) {
  cdyn::set_thread_count(static_cast<int>(state.range(0)));
  std::vector<double> a(kLength, 0.0), b(kLength, 1.0), c(kLength, 2.0);
  const double s = 3.0;
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (long i = 0; i < kLength; ++i) a[i] = b[i] + s * c[i];
    benchmark::ClobberMemory();
  }
  state.counters["GB/s"] = benchmark::Counter(3.0 * 8.0 * kLength * state.iterations() / 1e9,
                                              benchmark::Counter::kIsRate);
}

// The 9-point pattern of a k × k grid, diagonally dominant, symmetric.
cdyn::SparseMatrix nine_point(int k) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(9L * k * k);
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= k || jj >= k) continue;
          t.emplace_back(j * k + i, jj * k + ii, di == 0 && dj == 0 ? 9.0 : -1.0);
        }
  cdyn::SparseMatrix S(k * k, k * k);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

void product(benchmark::State& state) {
  cdyn::set_thread_count(static_cast<int>(state.range(0)));
  static const cdyn::SparseMatrix S = nine_point(1100);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(S.rows(), 0.0, 1.0);
  Eigen::VectorXd y(S.rows());
  for (auto _ : state) {
    y = cdyn::symmetric_times(S, x);
    benchmark::DoNotOptimize(y.data());
  }
  // values and row indices read once, x read (about) once, y written once
  const double bytes = 12.0 * S.nonZeros() + 16.0 * S.rows();
  state.counters["GB/s"] = benchmark::Counter(bytes * state.iterations() / 1e9, benchmark::Counter::kIsRate);
}

BENCHMARK(triad)->ArgName("threads")->Arg(1)->Arg(2)->Repetitions(5)->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(product)->ArgName("threads")->Arg(1)->Arg(2)->Repetitions(5)->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
