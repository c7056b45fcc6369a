// lanczos.hpp — the largest eigenpair of a symmetric operator by the Lanczos process
// with full reorthogonalization (Golub & Van Loan, "Matrix Computations", 4th ed., §10.1
// and §10.3.1; Parlett, "The Symmetric Eigenvalue Problem", ch. 13).
//
// Used by the sparse check of condition (12) (condition12_sparse.hpp) on the shifted
// inverse T = (G P Gᵀ − σ I)⁻¹, σ certified below β²: its largest eigenvalue 1/(β² − σ)
// is well separated from the next one once σ is close to β², so a few tens of steps
// converge and the whole Krylov basis is kept.  That is also why this is a plain
// Lanczos and not an implicitly restarted one (ARPACK, Spectra): with at most
// `max_steps` ≈ 40 vectors no restart ever happens, and a restarted method would reduce
// to the same iteration; the caller's shift strategy, not restarting, is what makes
// the clustered bottom of the spectrum of G P Gᵀ tractable.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace cdyn {

struct LanczosPair {
  double value = 0.0;          // the largest Ritz value τ
  Eigen::VectorXd vector;      // its Ritz vector, unit
  double second = 0.0;         // the next Ritz value (value when there is one step only)
  double residual = 0.0;       // ‖T y − τ y‖ (the Lanczos estimate β_j |s_j|)
  int steps = 0;               // applications of T
};

// The largest eigenpair of the symmetric operator T on R^n, from `start` (any nonzero
// vector).  Stops when residual ≤ tolerance(value, residual) says so, after `max_steps`,
// or when the Krylov space becomes invariant (then residual = 0: the pair is exact to
// round-off, e.g. n ≤ max_steps).
LanczosPair lanczos_largest(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& T,
                            const Eigen::VectorXd& start, int max_steps,
                            const std::function<bool(const LanczosPair&)>& converged);

}  // namespace cdyn
