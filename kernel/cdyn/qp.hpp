// qp.hpp — the bound-constrained quadratic program of one implicit time step.
//
// Every implicit scheme of DESIGN.md §1 solves, once per step,
//
//     min_X  ½ Xᵀ S X − rᵀ X    subject to   lower ≤ X ≤ upper,                  (QP)
//
// with S symmetric positive definite.  S is given either explicitly (a sparse matrix) or,
// for the mixed pairs whose velocity space H^h is continuous, through its saddle form
//
//     S = A + c Bᵀ C⁻¹ B          [[A, c Bᵀ], [B, −C]]                (seed eq. 11)
//
// where C⁻¹ is dense and never formed.  The obstacle constraint u(a_i) ≥ g(a_i) of the
// seed (eq. 16, G = −I on the constrained vertices) is a lower bound; a Signorini
// condition on an inclined plane becomes a bound after the node-local rotation of
// qp_rotation.hpp.  Unconstrained unknowns have bounds ∓infinity.
//
// KKT conditions.  With the reaction  λ = S X − r  (the force the constraint exerts,
// λ = Gᵀλ_seed for the seed's multiplier λ_seed ≤ 0 and G = −I), X solves (QP) iff
//     lower ≤ X ≤ upper,  λ_i ≥ 0 where X_i = lower_i,  λ_i ≤ 0 where X_i = upper_i,
//     λ_i = 0 where lower_i < X_i < upper_i.
// One measure of how far X is from satisfying them, used by every solver (docs/qp.md):
//     F(X) = X − P(X − D⁻¹ λ),   P the projection on the box,  D = diag(S),
//     kkt_residual(X) = ‖F(X)‖_∞ / max(‖X‖_∞, ‖D⁻¹ r‖_∞).
// F = 0 exactly at the solution; F measures infeasibility, stationarity and
// complementarity at once in units of X, and the quotient is invariant under scaling
// S, r or the bounds, so one `tol` means the same thing for every solver.
//
// The solvers (one file each): pdas (primal-dual active set, Hintermüller–Ito–Kunisch
// 2002, the default), pgs (projected Gauss–Seidel / SOR), ipopt (interior point),
// nlopt (L-BFGS with bounds, small problems).  make_step_solver picks one by name.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cdyn {

// Compressed sparse column (Eigen's default layout, int indices): passed to CHOLMOD and
// UMFPACK as it is, without copies.
using SparseMatrix = Eigen::SparseMatrix<double>;

// S = A + c Bᵀ C⁻¹ B given by its blocks: A (N_W × N_W, symmetric positive
// semidefinite), B (N_H × N_W), C (N_H × N_H, symmetric positive definite), c > 0
// (the scheme's mass factor, e.g. 1/dt² for backward Euler).
struct SaddleForm {
  SparseMatrix A, B, C;
  double c = 1.0;
};

// The problem (QP).  Give S, or leave it empty (0 × 0) and give `saddle`; not both.
// Full symmetric storage (both triangles).  Bounds may be ±infinity.
struct BoundQP {
  SparseMatrix S;
  std::optional<SaddleForm> saddle;
  Eigen::VectorXd r, lower, upper;

  int size() const { return static_cast<int>(r.size()); }
};

struct QPOptions {
  double tol = 1e-10;          // on kkt_residual, the same for every solver
  int max_iterations = 0;      // 0: the solver's own default (see each solver's header)
  bool throw_on_failure = true;  // false: return with converged = false instead of throwing
  // pdas: active-set changes of at most this many unknowns are applied to the current
  // Cholesky factor by row additions/deletions instead of refactorizing (0: always
  // refactor; −1: max(300, n/100), the break-even measured in docs/performance.md)
  int pdas_update_limit = -1;
  // pdas, explicit S: solve a system whose active set differs from the factorized one by
  // preconditioned conjugate gradients on S̃ (masked_cg.hpp; at most this many iterations; 0: never)
  // before touching the factor, when that is cheaper than the row updates (flop counts,
  // qp_pdas.cpp cg_pays).  Pays when S̃ is well conditioned — the step matrix of P1+/P0
  // with the bubbles condensed (condition O(1): about 3 iterations per decade of the
  // residual at any n, docs/performance.md) — and gives up at the cap otherwise (then never again for this
  // S).  The factor is brought to the current active set once that set has settled
  // (three solves in a row) or, if pdas_cg_resync ≥ 0, after that many CG iterations
  // since it was last (re)made.
  int pdas_cg_iterations = 80;
  int pdas_cg_resync = -1;
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
  double kkt_residual = 0.0;  // as kkt_residual() below, computed the same way by every solver
  double seconds = 0.0;      // wall time of solve()
  bool converged = false;    // kkt_residual ≤ tol (with throw_on_failure, always true on return)
};

// One object lives across all time steps; it may cache analyses and factorizations
// of S (keyed by S's pattern and values, so a changed S is always noticed).
class StepSolver {
 public:
  virtual ~StepSolver() = default;
  virtual std::string name() const = 0;
  // Throws InputError for inconsistent data (sizes, lower > upper, NaN/Inf, a form the
  // solver does not take) and NumericalError when S is not positive definite or the
  // solver does not reach tol.  `warm_start`: a previous result (its X and active set).
  virtual QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) = 0;
};

// name: "pdas" | "pgs" | "ipopt" | "nlopt"; anything else is an InputError.
std::unique_ptr<StepSolver> make_step_solver(const std::string& name, const QPOptions& options = {});
std::vector<std::string> step_solver_names();

// The common KKT measure (see above).  For the saddle form it factorizes C each call;
// solvers use the overload taking the gradient λ = S X − r they already have.
double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X);
double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                    const Eigen::VectorXd* D = nullptr);  // D = scaling_diagonal(qp) if already known

// ----- building blocks shared by the solvers ------------------------------------------

// Throws InputError when sizes disagree, S (or A, B, C) or r contain NaN/Inf, S is not
// symmetric, a bound is NaN, lower > upper somewhere (an empty feasible set), or both
// or neither of S and saddle are given.  matrices = false skips the O(nnz) checks of
// the matrices (see CheckedMatrices).
void check_problem(const BoundQP& qp, bool matrices = true);

// check_problem() (and, on request, check_positive_definite() of an explicit S) for a
// solver object that lives across time steps: the matrices are checked only when they
// differ from those of the last call (pattern or values), so a time loop with an
// unchanged S pays for the checks once.
class CheckedMatrices {
 public:
  // Returns true when the matrices were new (and have now been checked).
  bool check(const BoundQP& qp, bool positive_definite, const std::string& solver);

 private:
  bool valid_ = false;
  SparseMatrix S_, A_, B_, C_;
  double c_ = 0.0;
};

// D = diag(S); in saddle form diag(A) + c Σ_k B_kj² / C_kk (C replaced by its diagonal:
// a scaling, not the exact diagonal, which would need C⁻¹).
Eigen::VectorXd scaling_diagonal(const BoundQP& qp);

// F(X) = X − P(X − D⁻¹ λ), the natural residual of the KKT conditions.
Eigen::VectorXd natural_residual(const BoundQP& qp, const Eigen::VectorXd& X,
                                 const Eigen::VectorXd& reaction, const Eigen::VectorXd& D);

// Sparse Cholesky factorization P S Pᵀ = L D Lᵀ of an SPD matrix through CHOLMOD's C API,
// reading the Eigen matrix in place (no copy; lower triangle used).  analyze() once per
// pattern (fill-reducing ordering, pattern of L), factorize() per new values (supernodal
// when CHOLMOD finds it worth it), and between factorizations replace_by_identity() /
// restore() change one row and column of the factorized matrix (cholmod_rowdel /
// cholmod_rowadd: a rank-2 modification of L, Davis & Hager 2005) without refactorizing.
class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  void analyze(const SparseMatrix& S);
  bool analyzed_for(const SparseMatrix& S) const;  // same pattern as the last analyze()
  // Numeric factorization of S (pattern as analysed).  Returns −1, or the unknown at
  // which S was found not positive definite (the factor is then dropped).
  int factorize(const SparseMatrix& S);
  bool factorized() const;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // Row and column i of the factorized matrix become those of the identity.
  void replace_by_identity(int i);
  // Row and column i, identity before, become column i of S restricted to the rows with
  // keep[row] != 0 (keep[i] != 0).  Returns false if the result is not positive definite.
  bool restore(int i, const SparseMatrix& S, const std::vector<char>& keep);
  // Floating-point operations of the last replace_by_identity() or restore(), as CHOLMOD
  // counts them (cholmod_common::modfl): what PDAS weighs against a CG solve.
  double modification_flops() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// X ↦ S X for either form.  In saddle form C is factorized (CHOLMOD) when set() sees a
// new C, and S X = A X + c Bᵀ (C⁻¹ (B X))  (seed eq. 11).  A solver keeps one across
// calls; set() before use each time (it keeps a pointer to the problem).
class QuadraticForm {
 public:
  QuadraticForm();
  ~QuadraticForm();
  QuadraticForm(const QuadraticForm&) = delete;
  QuadraticForm& operator=(const QuadraticForm&) = delete;
  // same_matrices: qp's matrices are those of the last set() (CheckedMatrices::check
  // returned false): D and C's factor are kept, only the problem is rebound.
  void set(const BoundQP& qp, bool same_matrices = false);
  Eigen::VectorXd apply(const Eigen::VectorXd& X) const;
  double objective(const Eigen::VectorXd& X) const;  // ½ Xᵀ S X − rᵀ X
  const Eigen::VectorXd& diagonal() const { return D_; }  // scaling_diagonal(qp), computed by set()

 private:
  const BoundQP* qp_ = nullptr;
  Eigen::VectorXd D_;
  SparseMatrix C_;
  std::unique_ptr<SparseCholesky> c_factor_;
};

// Fills reaction, active, kkt_residual, converged of a result whose X is set, with the
// common measure.  `form` is the problem's QuadraticForm.
void finish_result(const BoundQP& qp, const QuadraticForm& form, double tol, QPResult& result);

// The unknowns at a bound according to the rule of QPResult::active.
std::vector<int> active_set(const BoundQP& qp, const Eigen::VectorXd& X,
                            const Eigen::VectorXd& reaction, const Eigen::VectorXd& D);

// Throws NumericalError naming the solver, the residual and the iteration count when
// result.converged is false and options.throw_on_failure is set.
void report_failure(const std::string& solver, const QPOptions& options, const QPResult& result,
                    const std::string& detail = "");

// True when a and b have the same pattern (and, with values = true, the same values).
bool same_matrix(const SparseMatrix& a, const SparseMatrix& b, bool values = true);

// Checks that the explicit S is positive definite (one CHOLMOD factorization); throws
// NumericalError naming the failing leading minor.  Used once per distinct S.
void check_positive_definite(const SparseMatrix& S, const std::string& what = "S");

}  // namespace cdyn
