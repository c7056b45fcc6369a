// linalg/threads.hpp — how many threads the kernel's loops and the BLAS under CHOLMOD use.
//
// The kernel's parallel loops (linalg/parallel.hpp and the loops written by its rules)
// are OpenMP loops: they take the threads of the OpenMP runtime, OMP_NUM_THREADS or, when
// it is not set, one per core (the OpenMP convention).  Their results do not depend on
// the count, bit for bit.
//
// CHOLMOD's supernodal factorization, and its solve with a factor whose entries sit mostly
// in wide supernodes (a 3D one: SupernodalSolve::suits in linalg/supernodal_solve.hpp;
// the kernel's own sweeps are plain loops), spend their time in the BLAS, whose threads
// are the BLAS's own: OpenBLAS reads OPENBLAS_NUM_THREADS, then OMP_NUM_THREADS, then
// takes one per core.  OpenBLAS on more than one thread factorizes and solves with other
// blockings (its threaded dpotrf, dgemv), which changes the factor's round-off: a
// forward/back solve by 1e-16 relative (measured, docs/performance.md "Both cores").
// So the two counts are set apart: a run is the same bit for bit on any number of
// threads for its loops as long as the BLAS keeps its count.
//
// Both counts are the process's — the OpenMP runtime's and the BLAS's, not a value an
// object of the kernel owns; 0 gives a count back to what the environment set.
#pragma once

#include <functional>

namespace cdyn {

// The threads a parallel loop of the kernel runs on (1 without OpenMP).
int thread_count();

// n ≥ 1: the kernel's loops on n threads; n = 0: the environment's count again (the one
// before the first call).  InputError (parameter "threads") for n < 0.
void set_thread_count(int n);

// Runs f, a call into a library, with the OpenMP threads its parallel regions take bounded
// by thread_count().  CHOLMOD 3's supernodal factorization asks for a fixed team of
// CHOLMOD_OMP_NUM_THREADS = 4 (cholmod_core.h) in its loops that clear and assemble L,
// whatever OMP_NUM_THREADS says: on this 2-core machine, with the kernel on one thread,
// every large supernode woke three workers (8 % of a chattering contact run's time, most
// of it in futex calls, docs/performance.md).  Done by a host teams region of one team
// with thread_limit = thread_count() (OpenMP 5.0); called inside a parallel region, f
// runs as it is (a nested region is then the runtime's to limit).  An exception f throws
// is passed on after the region.
void within_thread_count(const std::function<void()>& f);

// The threads of the BLAS if it is OpenBLAS; 0 when the BLAS cannot tell (another BLAS).
int blas_thread_count();

// The same for OpenBLAS (nothing with another BLAS).  InputError (parameter "threads")
// for n < 0.
void set_blas_thread_count(int n);

}  // namespace cdyn
