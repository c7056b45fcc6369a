// explicit_reduced_system.hpp — the reduced system S̃ X = b̃ of an active-set step
// (reduced_system.hpp) for an explicitly given S: a CHOLMOD factor kept across calls,
// moved between active sets by row updates, and preconditioned CG while the set moves.
//
// Why this much machinery.  A fresh factorization per active-set change costs about 25
// forward/back solves (DESIGN.md §3's measurement), and the contact zone of a time loop
// changes a few unknowns per step.  So:
//   - one CHOLMOD analysis per pattern serves every active set (S̃ keeps S's pattern);
//   - the numeric factor is kept across calls: a time loop whose S and active set do
//     not change pays one forward/back solve per step;
//   - a change of at most QPOptions::pdas_update_limit unknowns (default max(300, n/100))
//     is applied to the factor by cholmod_rowdel / cholmod_rowadd, rank-2 modifications
//     of L (Davis & Hager 2005, row modifications of a sparse Cholesky factorization);
//   - before touching the factor, a system whose active set differs from the factor's is
//     solved by CG on S̃ (linalg/masked_cg.hpp: symmetric Gauss–Seidel preconditioner)
//     when that costs fewer flops than the row updates (cg_pays).  On a well-conditioned
//     S — the condensed P1+/P0 step matrix — a CG iteration costs a seventh to a fifth
//     of a forward/back solve, against hundreds of row updates (0.1–0.2 solve each, and
//     slower solves after them) or a factorization when the contact zone jumps;
//   - once an active set has served three calls (time steps: a scheme's repeated solves
//     of one step count once, StepSolver::next_in_same_step) in a row the contact zone
//     has settled, and the factor is brought to it (resync_due), so that the coming
//     steps are one forward/back solve each again — where that pays (resync_pays): the
//     settled sets seen so far tell how many more calls one serves, and a contact zone that settles
//     for a few steps and moves again (chattering) does not repay a refactorization;
//   - when most unknowns are held (resting contact: a body lying on the obstacle), S̃
//     in S's pattern still has the fill of the whole S, while the free block S_II alone
//     is much smaller: a refactorization for a set that leaves at most
//     QPOptions::pdas_free_block of the unknowns free factorizes S̃ on I⁺ = I ∪ M only,
//     M the held neighbours of I, whose unknowns that switch within I⁺ are row updates
//     on it (qp/pdas/free_block_factor.hpp).
//   - S's own factor (nothing held) is kept aside when the factor first leaves it, and
//     taken back, a copy, when nothing is held again (a body lifted off): the steps are
//     then the linear step's one solve, where CG pairs and a refactorization would be;
//   - while the factor is S's own, a set that holds a few unknowns (a membrane touching
//     the obstacle here and there) is solved with it and the capacitance matrix of the
//     held unknowns (qp/pdas/capacitance_solve.hpp): one solve's cost, exact, where a
//     CG pair costs about three, when its new columns and matrix cost at most twice
//     what that pair costs beyond the solve (capacitance_pays).
// A new S is first factorized whole: that checks it is positive definite (CHOLMOD's LLᵀ
// stops at the first non-positive pivot: NumericalError naming the unknown) and is the
// unconstrained solve of a cold start.
//
// QPOptions::pdas_cg_only: no factor at all, every system by CG (large 3D problems,
// whose factor does not fit or costs more than the CG iterations).
#pragma once

#include <optional>
#include <string>

#include "cdyn/linalg/masked_cg.hpp"
#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/qp/pdas/capacitance_solve.hpp"
#include "cdyn/qp/pdas/free_block_factor.hpp"
#include "cdyn/qp/pdas/reduced_system.hpp"

namespace cdyn {

class ExplicitReducedSystem : public ReducedSystem {
 public:
  // options and counters are referenced: they must outlive this object.
  ExplicitReducedSystem(const QPOptions& options, PDASCounters& counters);

  void prepare(const BoundQP& qp, bool new_matrices) override;
  Eigen::VectorXd solve_fixed(const BoundQP& qp, const HeldSet& held, const Eigen::VectorXd& value,
                              double tol) override;
  void reaction(const BoundQP& qp, const QuadraticForm& form, const Eigen::VectorXd& X, const HeldSet& held,
                Eigen::VectorXd& lam, const Iterate* previous = nullptr) const override;
  void set_held(const HeldSet& held, bool fresh = false) override;
  Eigen::VectorXd solve_correction(const Eigen::VectorXd& b, double tol) override;
  double last_residual() const override { return last_cg_residual_; }
  bool last_inexact() const override { return last_by_cg_; }
  void resume_next() override { resume_cg_ = true; }
  void set_first_guess(const Eigen::VectorXd& X) override { y_last_ = X; }
  // The next prepare() is the last call's time step again, its systems solved by the
  // factor if to_round_off (StepSolver::next_in_same_step).
  void next_in_same_step(bool to_round_off) {
    same_step_next_ = true;
    round_off_next_ = to_round_off;
  }
  bool refactorization_may_help() const override {
    return !opt_.pdas_cg_only && (way_ != Way::Factor || updates_since_factorization_ > 0);
  }

 private:
  void refactorize(const HeldSet& held);
  void factor_made_for(const HeldSet& held);
  void take_whole_factor();
  void leave_whole_factor();
  // Whether a refactorization for a set leaving n_free unknowns free factorizes the free
  // block alone (QPOptions::pdas_free_block): what refactorize does and sync_cost prices.
  bool factorizes_free_block(long n_free) const { return n_free <= opt_.pdas_free_block * n_; }
  void sync_factor(const HeldSet& held);
  int update_limit() const;
  bool refactorization_pays(int changes) const;
  bool priced_as_refactorization(int changes) const;
  bool resync_due(const HeldSet& held) const;
  bool resync_pays(const HeldSet& held) const;
  struct Sync {
    double flops, solve_flops;
  };
  Sync sync_cost(const HeldSet& held) const;
  bool cg_pays(const HeldSet& held) const;
  bool capacitance_pays(const HeldSet& held);
  double cg_iteration_flops() const;
  double cg_pair_flops() const;
  void track_run(const HeldSet& held);
  const Eigen::VectorXd& solve_tilde(const Eigen::VectorXd& b, double cg_tol);  // into y_last_
  void build_rhs(const BoundQP& qp, const HeldSet& held, const Eigen::VectorXd& value);  // b̃, into b_
  Eigen::VectorXd solve_by_capacitance(const BoundQP& qp, const Eigen::VectorXd& value);

  const QPOptions& opt_;
  PDASCounters& counters_;
  int n_ = 0;
  SparseMatrix S_, S_tilde_;              // the last S seen; S with the held set eliminated
  int bandwidth_ = 0;                     // max |i − j| over S_'s entries
  SparseCholesky chol_;
  HeldSet factor_held_;                   // the held set the factor currently factorizes
  // Most unknowns held (QPOptions::pdas_free_block): the factor is that of S̃ on I⁺ alone.
  bool block_mode_ = false;               // the factor is block_'s, not chol_'s
  FreeBlockFactor block_;
  int updates_since_factorization_ = 0;
  // S's own factor (no unknown held): chol_'s now, or kept aside by chol_ (keep()) since
  // chol_ was first refactorized or updated for a held set, so that the empty held set
  // (the body lifted off) costs a copy of it and not a factorization.
  bool whole_in_chol_ = false;
  // How solve_tilde solves the held set of the last set_held: by the factor (that set's),
  // by CG on S̃ (cg_held_, QPOptions::pdas_cg_iterations), or by S's own factor and the
  // capacitance matrix of the held unknowns (a few held, capacitance_).
  enum class Way { Factor, Cg, Capacitance };
  Way way_ = Way::Factor;
  bool cg_failed_ = false;                // CG did not converge once for this S: not tried again
  HeldSet cg_held_;
  int cg_since_sync_ = 0;                 // CG iterations since the factor was last (re)made
  int cg_mode_uses_ = 0;                  // calls in a row that used cg_held_ (resync_due)
  int calls_ = 0, cg_held_call_ = 0;      // time steps (prepare() calls) so far; the last that used cg_held_
  bool same_step_next_ = false;           // the next prepare() is the last one's step again
  bool round_off_next_ = false;           // and its systems are solved by the factor
  bool by_factor_ = false;                // this call's are (set_held)
  std::optional<MaskedCG> cg_;            // CG on S_ (its preconditioner, work vectors, last residual)
  CapacitanceSolve capacitance_;          // its columns (of chol_'s factor of S) and matrix
  bool capacitance_has_r_ = false;        // it holds L⁻¹ P r for this QP's r (solve_by_capacitance)
  Eigen::VectorXd b_;                     // the last solve_fixed's b̃
  Eigen::VectorXd y_last_;                // the last solution of solve_tilde: CG's first guess
  double last_cg_residual_ = 0.0;         // CG's scaled residual in the last solve_tilde (0: by the factor)
  bool last_by_cg_ = false;               // the last solve_tilde was a converged CG solve
  bool resume_cg_ = false;                // the next solve_tilde repeats the last one at a smaller tol
  // What the two ways to a new active set have cost so far on this pattern (flops as
  // CHOLMOD counts them for a row update; CG iterations), for cg_pays().
  double update_flops_ = 0.0;
  int updates_measured_ = 0;
  // Runs of one held set over consecutive calls, whatever solved them (resync_pays): the
  // current run, and the runs that reached kSettled calls with the calls they served from
  // the kSettled-th on (those a resync would have served by the factor).
  static constexpr int kSettled = 3;
  HeldSet run_held_;
  int run_uses_ = 0, run_call_ = -1;
  int settled_runs_ = 0;
  double settled_uses_ = 0.0;
};

}  // namespace cdyn
