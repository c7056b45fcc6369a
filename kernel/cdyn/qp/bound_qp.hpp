// bound_qp.hpp — the bound-constrained quadratic program of one implicit time step.
//
// Every implicit scheme of docs/schemes.md solves, once per step,
//
//     min_X  ½ Xᵀ S X − rᵀ X    subject to   lower ≤ X ≤ upper,                  (QP)
//
// with S symmetric positive definite.  S is given either explicitly (a sparse matrix) or,
// for the mixed pairs whose velocity space H^h is continuous, through its saddle form
//
//     S = A + c Bᵀ C⁻¹ B          [[A, c Bᵀ], [B, −C]]                (seed eq. 11)
//
// where C⁻¹ is dense and never formed (base/sparse.hpp).  The obstacle constraint
// u(a_i) ≥ g(a_i) of the seed (eq. 16, G = −I on the constrained vertices) is a lower
// bound; a Signorini condition on an inclined plane becomes a bound after the node-local
// rotation of problems/nodal_rotation.hpp.  Unconstrained unknowns have bounds ∓infinity.
//
// KKT conditions.  With the reaction  λ = S X − r  (the force the constraint exerts,
// λ = Gᵀλ_seed for the seed's multiplier λ_seed ≤ 0 and G = −I), X solves (QP) iff
//     lower ≤ X ≤ upper,  λ_i ≥ 0 where X_i = lower_i,  λ_i ≤ 0 where X_i = upper_i,
//     λ_i = 0 where lower_i < X_i < upper_i.
// How far X is from them is measured by kkt_residual (qp/kkt.hpp), the same for every
// solver.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

// The problem (QP).  Give S, or leave it empty (0 × 0) and give `saddle`; not both.
// Full symmetric storage (both triangles).  Bounds may be ±infinity.
struct BoundQP {
  SparseMatrix S;
  std::optional<SaddleForm> saddle;
  Eigen::VectorXd r, lower, upper;
  // The name of the matrices (S, or saddle's A, B, C and c), given by the one who keeps
  // this QP across calls: a number from new_matrices_id(), renewed whenever it changes
  // them.  A solver that saw the same nonzero name at its last call takes the matrices as
  // unchanged without reading them — in a time loop, comparing S with the solver's copy
  // read every stored entry twice per solve, a pass over S as long as a product with it
  // (PETSc names its objects' states the same way).  0: unnamed, compared entry by entry.
  std::uint64_t matrices_id = 0;

  int size() const { return static_cast<int>(r.size()); }
};

// A name for matrices never given before in this process (BoundQP::matrices_id).
inline std::uint64_t new_matrices_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

struct QPOptions {
  double tol = 1e-10;          // on kkt_residual, the same for every solver
  int max_iterations = 0;      // 0: the solver's own default (see each solver's header)
  bool throw_on_failure = true;  // false: return with converged = false instead of throwing
  // pdas: active-set changes of at most this many unknowns are applied to the current
  // Cholesky factor by row additions/deletions instead of refactorizing (0: always
  // refactor; −1: max(300, n/100), the break-even measured in docs/performance.md)
  int pdas_update_limit = -1;
  // pdas, explicit S: solve a system whose active set differs from the factorized one by
  // preconditioned conjugate gradients on S̃ (linalg/masked_cg.hpp; at most this many iterations; 0: never)
  // before touching the factor, when that is cheaper than the row updates (flop counts,
  // qp/pdas, cg_pays).  Pays when S̃ is well conditioned — the step matrix of P1+/P0
  // with the bubbles condensed (condition O(1): about 3 iterations per decade of the
  // residual at any n, docs/performance.md) — and gives up at the cap otherwise (then never again for this
  // S).  The factor is brought to the current active set once that set has settled
  // (three solves in a row) or, if pdas_cg_resync ≥ 0, after that many CG iterations
  // since it was last (re)made.
  int pdas_cg_iterations = 80;
  int pdas_cg_resync = -1;
  // pdas, explicit S: CG for every set other than the factor's until it settles, even
  // where the flop counts say a refactorization or row updates cost less (small or
  // nearly banded S): to exercise and compare the CG path on small problems.
  bool pdas_cg_always = false;
  // pdas, explicit S: a (re)factorization for an active set that leaves at most this
  // fraction of the unknowns free factorizes the free block S_II alone, with its own
  // fill-reducing ordering, instead of S̃ in S's pattern (whose fill does not shrink with
  // the free set); 0: never.  Resting contact, most unknowns on the obstacle.
  double pdas_free_block = 0.5;
  // pdas, explicit S: a set holding a few unknowns, while the factor is S's own, solved
  // with that factor and the dense capacitance matrix of the held unknowns
  // (qp/pdas/capacitance_solve.hpp: one solve's cost, exact) where its columns and
  // matrix cost at most twice what the set's CG pair costs beyond one solve (one solve
  // before any CG solve is measured), before CG or moving the factor — if a solve
  // with S's factor costs at least this many flops (10⁶: the membrane from n = 160 on;
  // on smaller problems its fixed work outweighs what it saves); infinity: never.
  double pdas_capacitance_from = 1e6;
  // pdas, explicit S: never factorize; every reduced system S̃ by the masked CG above, at
  // most max(pdas_cg_iterations, 2000) iterations a solve (NumericalError beyond).  The
  // path for large 3D problems, whose Cholesky factor fills far more than in 2D while
  // the step matrix stays well conditioned when dt ∝ h (docs/performance.md).  Not for
  // the saddle form (P1+/P1, P2/P1), which is always solved by UMFPACK: InputError.
  bool pdas_cg_only = false;
  double pgs_omega = 1.0;      // pgs: over-relaxation factor, 0 < ω < 2
  int pgs_check_every = 10;    // pgs: sweeps between two evaluations of the KKT residual
  bool ipopt_crossover = true;  // ipopt: finish by PDAS steps from Ipopt's active set if above tol
  std::string nlopt_algorithm = "LD_LBFGS";  // nlopt: LD_LBFGS or LD_CCSAQ
  int nlopt_polish_rounds = 3;  // nlopt: active-set identification + reduced solve after it stops
};

struct QPResult {
  Eigen::VectorXd X;
  Eigen::VectorXd reaction;  // λ = S X − r: ≥ 0 at active lower bounds, ≤ 0 at active upper, ~0 elsewhere
  std::vector<int> active;   // unknowns at a bound: λ_i > D_ii (X_i − lower_i) or λ_i < D_ii (X_i − upper_i)
  int iterations = 0;        // pdas: linear solves; pgs: sweeps; ipopt: IP iterations; nlopt: evaluations
  double kkt_residual = 0.0;  // as kkt_residual() (qp/kkt.hpp), computed the same way by every solver
  double seconds = 0.0;      // wall time of solve()
  bool converged = false;    // kkt_residual ≤ tol (with throw_on_failure, always true on return)
};

}  // namespace cdyn
