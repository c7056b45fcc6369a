// saddle_reduced_system.cpp — S̃ X = b̃ through UMFPACK's LU of the saddle matrix
// [[A, c Bᵀ], [c B, −c C]] (the second block row scaled by c, for symmetry) with the held
// unknowns eliminated; see saddle_reduced_system.hpp.
#include "cdyn/qp/pdas/saddle_reduced_system.hpp"

#include <Eigen/UmfPackSupport>
#include <algorithm>

#include "cdyn/base/error.hpp"

namespace cdyn {

// UMFPACK's 64-bit interface (umfpack_dl): the 32-bit one addresses at most 2³¹ words
// of workspace, which the LU of a 3D P2/P1 saddle matrix exceeds (measured: the cube at
// n = 16, 122 550 rows, "out of memory" at 3 GB; with umfpack_dl it runs, 11.2 GB and
// 76 s a step).  K̃ is copied into 64-bit indices for it.
using LongMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;
struct SaddleReducedSystem::LU {
  LongMatrix K;  // K̃ as UMFPACK reads it (UmfPackLU keeps a reference)
  Eigen::UmfPackLU<LongMatrix> umfpack;
};

SaddleReducedSystem::SaddleReducedSystem(PDASCounters& counters)
    : counters_(counters), lu_(std::make_unique<LU>()) {
  // The matrix is symmetric (its second block row scaled by c): UMFPACK's symmetric
  // strategy keeps AMD's fill-reducing order and prefers diagonal pivots.  One step of
  // iterative refinement instead of UMFPACK's default two (measured: P2/P1 membrane,
  // n = 40, 8.5 → 7.0 ms a step QP; none at all gave 2.6 ms, but the energy identities
  // of the midpoint rule then held to 3e-11 instead of round-off, 1e-13, over 1000 steps).
  lu_->umfpack.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  lu_->umfpack.umfpackControl()(UMFPACK_IRSTEP) = 1;
}
SaddleReducedSystem::~SaddleReducedSystem() = default;

void SaddleReducedSystem::prepare(const BoundQP& qp, bool new_matrices) {
  n_ = qp.size();
  if (!new_matrices && lu_factorized_) return;
  const SaddleForm& f = *qp.saddle;
  if (lu_factorized_ && f.c == blocks_.c && same_matrix(f.A, blocks_.A) && same_matrix(f.B, blocks_.B) &&
      same_matrix(f.C, blocks_.C))
    return;
  blocks_ = f;
  SparseMatrix K = symmetric_saddle_matrix(f);
  const bool same_pattern = same_matrix(K, K_, false) && lu_factorized_;
  K_ = std::move(K);
  K_tilde_ = K_;
  if (!same_pattern) {
    lu_->K = K_;
    lu_->umfpack.analyzePattern(lu_->K);
    ++counters_.analyses;
    if (lu_->umfpack.info() != Eigen::Success)
      throw NumericalError("pdas: UMFPACK could not analyse the saddle matrix [[A, c B^T], [B, -C]]");
  }
  lu_factorized_ = false;
}

void SaddleReducedSystem::set_held(const HeldSet& held, bool fresh) {
  if (lu_factorized_ && held == lu_held_ && !fresh) return;
  replace_held_by_identity(K_, held, K_tilde_);
  std::copy(K_tilde_.valuePtr(), K_tilde_.valuePtr() + K_tilde_.nonZeros(), lu_->K.valuePtr());  // same pattern
  lu_->umfpack.factorize(lu_->K);
  ++counters_.factorizations;
  if (lu_->umfpack.info() != Eigen::Success) {
    // UMFPACK's status tells a singular matrix from a factorization it could not hold
    const int status = static_cast<int>(lu_->umfpack.umfpackFactorizeReturncode());
    if (status == UMFPACK_WARNING_singular_matrix)
      throw NumericalError("pdas: UMFPACK found the saddle matrix singular (is C positive definite and "
                           "A + c B^T C^-1 B positive definite?)");
    throw NumericalError("pdas: UMFPACK could not factorize the saddle matrix of " + std::to_string(K_tilde_.rows()) +
                         " rows (status " + std::to_string(status) +
                         (status == UMFPACK_ERROR_out_of_memory ? ": out of memory, its LU's fill" : "") + ")");
  }
  lu_factorized_ = true;
  lu_held_ = held;
}

// K̃ [y; z] = [top; bottom]; returns y.
Eigen::VectorXd SaddleReducedSystem::solve_tilde(const Eigen::VectorXd& top, const Eigen::VectorXd& bottom) {
  ++counters_.solves;
  const int m = static_cast<int>(K_.rows()) - n_;
  Eigen::VectorXd b(n_ + m);
  b.head(n_) = top;
  b.tail(m) = blocks_.c * bottom;
  Eigen::VectorXd y = lu_->umfpack.solve(b);
  return y.head(n_);
}

Eigen::VectorXd SaddleReducedSystem::solve_fixed(const BoundQP& qp, const HeldSet& held,
                                                 const Eigen::VectorXd& value, double) {
  set_held(held);
  // X rows: r_I − A_IA X_A (X_A on the held rows); Z rows: −B_A X_A.
  Eigen::VectorXd top = qp.r;
  Eigen::VectorXd bottom = Eigen::VectorXd::Zero(blocks_.C.rows());
  for (int j = 0; j < n_; ++j)
    if (held[j]) {
      for (SparseMatrix::InnerIterator it(blocks_.A, j); it; ++it) top[it.row()] -= it.value() * value[j];
      for (SparseMatrix::InnerIterator it(blocks_.B, j); it; ++it) bottom[it.row()] -= it.value() * value[j];
    }
  copy_held_values(held, value, top);
  Eigen::VectorXd X = solve_tilde(top, bottom);
  copy_held_values(held, value, X);
  return X;
}

Eigen::VectorXd SaddleReducedSystem::solve_correction(const Eigen::VectorXd& b, double) {
  return solve_tilde(b, Eigen::VectorXd::Zero(blocks_.C.rows()));
}

}  // namespace cdyn
