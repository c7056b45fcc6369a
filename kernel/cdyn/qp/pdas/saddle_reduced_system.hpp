// saddle_reduced_system.hpp — the reduced system S̃ X = b̃ of an active-set step
// (reduced_system.hpp) when S = A + c Bᵀ C⁻¹ B is given by its saddle form (seed eq. 11;
// C⁻¹ is dense for a continuous velocity space, so S is never formed).
//
// With Z = C⁻¹ B X the stationarity equations of the QP on the free unknowns read
//     [[A, c Bᵀ], [c B, −c C]] [X; Z] = [r; 0]   on the rows of X in I and all rows of Z,
// and the held unknowns are eliminated from the X rows and columns of this matrix K
// exactly as from S: K̃ = K with those rows and columns replaced by the identity's, in
// K's pattern, and B_A X_A moved to the right-hand side of the Z rows.  K is symmetric
// indefinite (the −C block), so the factorization is an LU, by UMFPACK (through Eigen's
// UmfPackLU, no copy): its symbolic analysis is kept while K's pattern does not change,
// its numeric LU for the last held set.  UMFPACK has no row updates: a new held set is a
// new numeric factorization.  K is singular exactly when A + c BᵀC⁻¹B restricted to the
// free unknowns is (C being positive definite): NumericalError.
#pragma once

#include <memory>

#include "cdyn/qp/pdas/reduced_system.hpp"

namespace cdyn {

class SaddleReducedSystem : public ReducedSystem {
 public:
  // counters is referenced: it must outlive this object.
  explicit SaddleReducedSystem(PDASCounters& counters);
  ~SaddleReducedSystem() override;

  void prepare(const BoundQP& qp, bool new_matrices) override;
  Eigen::VectorXd solve_fixed(const BoundQP& qp, const HeldSet& held, const Eigen::VectorXd& value,
                              double tol) override;
  void set_held(const HeldSet& held, bool fresh = false) override;
  Eigen::VectorXd solve_correction(const Eigen::VectorXd& b, double tol) override;
  // Always "yes", so that the iteration retries once before it reports a failure.  In
  // fact UMFPACK's numeric LU of the same K̃ is the same LU (its pivots are chosen by
  // the kept analysis of K): the retry repeats the solve.
  bool refactorization_may_help() const override { return true; }

 private:
  Eigen::VectorXd solve_tilde(const Eigen::VectorXd& top, const Eigen::VectorXd& bottom);

  PDASCounters& counters_;
  int n_ = 0;
  SaddleForm blocks_;         // the last blocks seen
  SparseMatrix K_, K_tilde_;  // [[A, c Bᵀ], [c B, −c C]] and its copy with the held set eliminated
  struct LU;                  // UMFPACK's (kept out of this header: SuiteSparse's are not public)
  std::unique_ptr<LU> lu_;
  bool lu_factorized_ = false;
  HeldSet lu_held_;
};

}  // namespace cdyn
