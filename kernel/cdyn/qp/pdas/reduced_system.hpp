// reduced_system.hpp — the linear algebra of one active-set step, behind one interface.
//
// Every iterate of the primal-dual active set method (pdas.hpp) and every direction of
// the projected Newton fallback (projected_newton.hpp) solves the QP's stationarity
// equations on the free unknowns I with the held ones A at given values:
//
//     S_II X_I = r_I − S_IA X_A.
//
// The implementations solve it as  S̃ X = b̃,  where S̃ is S with the rows and columns of A
// replaced by the identity's and b̃_I = r_I − S_IA X_A, b̃_A = X_A.  Written in S's own
// pattern (explicit zeros where the held entries were), S̃ has the same sparsity for
// every active set, so one symbolic analysis serves them all and a factor can be moved
// from one set to the next by row modifications (Davis & Hager 2005) instead of being
// rebuilt.  Two implementations:
//   - explicit_reduced_system.hpp: S given; CHOLMOD factor kept across calls, row
//     updates, and preconditioned CG on S̃ when that is cheaper;
//   - saddle_reduced_system.hpp: S = A + c Bᵀ C⁻¹ B given by its blocks (seed eq. 11);
//     UMFPACK's LU of the saddle matrix with the same elimination.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "cdyn/base/scope_timer.hpp"
#include "cdyn/qp/bound_qp.hpp"
#include "cdyn/qp/quadratic_form.hpp"

namespace cdyn {

class SparseCholesky;

// The work a PDAS solver's linear algebra has done (PDASSolver::Counters).
struct PDASCounters {
  int analyses = 0;        // symbolic analyses (CHOLMOD or UMFPACK)
  int factorizations = 0;  // numeric factorizations
  int row_updates = 0;     // cholmod_rowadd / cholmod_rowdel calls
  int solves = 0;          // forward/back solves
  int damped_iterations = 0;  // projected Newton iterations after a detected cycle
  int cg_solves = 0;       // systems solved by preconditioned CG instead of the factor
  int cg_iterations = 0;   // their CG iterations (one product with S each)
  int capacitance_solves = 0;   // systems solved with S's factor and a capacitance matrix
  int capacitance_columns = 0;  // its columns L⁻¹ P e_i made (one per newly held unknown)
  // Wall time in each kind of linear algebra (explicit S; for profiling, bench/):
  double factorization_s = 0, row_update_s = 0, solve_s = 0, cg_s = 0, capacitance_s = 0;
};

// held[i] ≠ 0: unknown i is held at a bound (it is in the active set A).
using HeldSet = std::vector<char>;

// How accurately an inexact (CG) solve of the reduced system is asked for: a bound on
// the Jacobi-scaled residual max_{i∉A} |b̃ − S̃X|_i / S_ii, which on the free unknowns is
// the natural residual that kkt_residual measures (qp/kkt.hpp), so the tolerance is in
// the QP's own units.  The scale is max(‖D⁻¹r‖∞, ‖X_A‖∞), a lower bound of
// kkt_residual's.  tight: tol/2 (the other half is a margin for the drift of CG's
// updated residual from the true one), for a solution; loose: 1e-4 of the scale, for a
// PDAS iterate, which only has to point to the next active set (inexact semismooth
// Newton: the loose iterates do not change where the iteration ends, only its cost).
class SolveTolerance {
 public:
  SolveTolerance(const BoundQP& qp, const Eigen::VectorXd& D, double tol);
  double operator()(const Eigen::VectorXd& held_values, bool tight) const;
  double operator()(double held_max, bool tight) const;  // held_max = ‖X_A‖∞
  double r_scale() const { return r_scale_; }           // ‖D⁻¹r‖∞

 private:
  double tol_, r_scale_;
};

// The reduced system of the current problem and active set.  A solver object keeps one
// across calls (and time steps), with whatever factorizations it has.
class ReducedSystem {
 public:
  virtual ~ReducedSystem() = default;

  // Once per call of the QP solver: makes the cached analysis and factorization those of
  // qp's matrices; new_matrices: they differ from the last call's (CheckedMatrices).
  virtual void prepare(const BoundQP& qp, bool new_matrices) = 0;

  // The minimizer with X_A = value_A: S̃ X = b̃ (X_A = value_A exactly).  tol: the scaled
  // residual an inexact solve must reach (SolveTolerance); direct solves ignore it.
  virtual Eigen::VectorXd solve_fixed(const BoundQP& qp, const HeldSet& held, const Eigen::VectorXd& value,
                                      double tol) = 0;
  // λ = S X − r for the X that solve_fixed has just returned for `held`, into lam.
  // previous: the last iterate of the same QP, with lam = λ at its X on entry (or null).
  struct Iterate {
    const Eigen::VectorXd& X;
    const HeldSet& held;
  };
  virtual void reaction(const BoundQP& qp, const QuadraticForm& form, const Eigen::VectorXd& X, const HeldSet& held,
                        Eigen::VectorXd& lam, const Iterate* previous = nullptr) const;

  // Makes the next solves those of `held` (fresh: a new factorization from scratch).
  virtual void set_held(const HeldSet& held, bool fresh = false) = 0;
  // y with S̃ y = b for the current held set (y_A = b_A): a correction or a direction,
  // so an iterative solve starts from zero.
  virtual Eigen::VectorXd solve_correction(const Eigen::VectorXd& b, double tol) = 0;

  // Inexact solves.  The scaled residual the last solve reached (0: a direct solve);
  // whether it was inexact; resume_next(): the next solve_fixed is the last one again
  // (the same held set and values) at a smaller tol, so the interrupted iteration may go
  // on from the same right-hand side; set_first_guess(): where
  // the next iterative solve starts (the previous result, or the warm start).
  virtual double last_residual() const { return 0.0; }
  virtual bool last_inexact() const { return false; }
  virtual void resume_next() {}
  virtual void set_first_guess(const Eigen::VectorXd&) {}

  // Whether a factorization from scratch may solve more accurately than the current
  // way (after row updates, CG, or an LU whose pivots were chosen for another matrix).
  virtual bool refactorization_may_help() const = 0;
};

// out = M with the rows and columns i < held.size(), held[i] ≠ 0, replaced by the
// identity's.  `out` has M's pattern (a copy of M): only the values are written.
void replace_held_by_identity(const SparseMatrix& M, const HeldSet& held, SparseMatrix& out);

// v_i = value_i on the held unknowns (the identity rows of S̃: b̃_A = X_A, and X_A exactly
// after a solve), v unchanged elsewhere.
void copy_held_values(const HeldSet& held, const Eigen::VectorXd& value, Eigen::VectorXd& v);

// A numeric factorization of `matrix` by `factor` (timed and counted in `counters`);
// NumericalError "pdas: <what> at unknown i)" if CHOLMOD finds it not positive definite,
// i the QP's unknown (unknowns[row] when the matrix is a block of S).
void factorize_counted(SparseCholesky& factor, const SparseMatrix& matrix, const std::string& what,
                       PDASCounters& counters, const std::vector<int>* unknowns = nullptr);

// Row updates of `factor`, the factor of S̃ for `held` (both in S's numbering): the
// unknowns to_delete become held (rows and columns the identity's, cholmod_rowdel), those
// to_add free (restored from S, cholmod_rowadd); `held` follows, their flops (CHOLMOD's
// modfl) are added to `flops`.  False when a restore finds the matrix not positive
// definite (round-off: a refactorization is due).
bool update_held(SparseCholesky& factor, const SparseMatrix& S, HeldSet& held, const std::vector<int>& to_delete,
                 const std::vector<int>& to_add, double& flops);

}  // namespace cdyn
