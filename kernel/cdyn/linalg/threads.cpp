// linalg/threads.cpp — the OpenMP runtime's thread count and OpenBLAS's; see linalg/threads.hpp.
#include "cdyn/linalg/threads.hpp"

#include <dlfcn.h>

#include <exception>
#include <string>

#include "cdyn/base/error.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace cdyn {

namespace {

void check_count(int n) {
  if (n < 0) throw InputError("threads", "must be 0 (the environment's count) or more (got " + std::to_string(n) + ")");
}

// OpenBLAS's own functions, looked up in the process rather than linked: CHOLMOD links
// the system's BLAS (libblas.so.3: OpenBLAS or another, through Debian's alternatives),
// and only OpenBLAS has them.
using GetThreads = int (*)();
using SetThreads = void (*)(int);
GetThreads openblas_get() { return reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads")); }
SetThreads openblas_set() { return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")); }

}  // namespace

int thread_count() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

void set_thread_count(int n) {
  check_count(n);
#ifdef _OPENMP
  static const int environment = omp_get_max_threads();  // read before the first change
  omp_set_num_threads(n > 0 ? n : environment);
#endif
}

void within_thread_count(const std::function<void()>& f) {
#ifdef _OPENMP
  if (!omp_in_parallel()) {
    const int limit = thread_count();
    std::exception_ptr thrown;  // an exception may not leave the teams region
#pragma omp teams num_teams(1) thread_limit(limit)
    {
      try {
        f();
      } catch (...) {
        thrown = std::current_exception();
      }
    }
    if (thrown) std::rethrow_exception(thrown);
    return;
  }
#endif
  f();
}

int blas_thread_count() {
  const GetThreads get = openblas_get();
  return get ? get() : 0;
}

void set_blas_thread_count(int n) {
  check_count(n);
  static const int environment = blas_thread_count();  // read before the first change
  const SetThreads set = openblas_set();
  const int count = n > 0 ? n : environment;
  if (set && count > 0) set(count);
}

}  // namespace cdyn
