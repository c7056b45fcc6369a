// linalg/prefetch.hpp — asking for the cache lines a sweep will read, ahead of the reads.
//
// The sweeps of a factor (linalg/supernodal_solve.cpp) and the products with a sparse
// matrix (linalg/parallel.cpp) read long arrays in storage order, a few hundred bytes at a
// time between other work.  Out of cache the processor's own prefetcher does not keep up
// with such short runs: perf put about half of their samples on their loads.  Asking a
// fixed distance ahead took 12 % off the free step at n = 640, 16 % at n = 320 and 11 %
// at n = 160 (docs/performance.md, (c)).  A prefetch changes no value and never faults,
// so the addresses are made as integers: near the ends of an array they lie outside it,
// where a pointer may not point.
#pragma once

#include <cstdint>

namespace cdyn {

// The line of p[k].
template <class T>
inline void prefetch_line(const T* p, long k) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(p) + k * sizeof(T)));
}

// The lines of p[from] … p[from + length − 1] (8 doubles a 64-byte line).
inline void prefetch_lines(const double* p, long from, long length) {
  for (long r = 0; r < length; r += 8) prefetch_line(p, from + r);
}

}  // namespace cdyn
