// quadratic_form.cpp — X ↦ S X, explicitly or through the saddle form (seed eq. 11).
#include "cdyn/qp/quadratic_form.hpp"

#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/qp/kkt.hpp"

namespace cdyn {

QuadraticForm::QuadraticForm() = default;
QuadraticForm::~QuadraticForm() = default;

void QuadraticForm::set(const BoundQP& qp, bool same_matrices) {
  const bool keep = same_matrices && qp_ != nullptr && D_.size() == qp.size();
  qp_ = &qp;
  if (keep) return;  // (a pass over S saved per step: the time loop's matrices do not change)
  D_ = scaling_diagonal(qp);
  if (!qp.saddle) return;
  const SparseMatrix& C = qp.saddle->C;
  if (c_factor_ && same_matrix(C, C_)) return;
  C_ = C;
  C_.makeCompressed();
  c_factor_ = std::make_unique<SparseCholesky>();
  c_factor_->analyze(C_);
  const int minor = c_factor_->factorize(C_);
  if (minor >= 0) {
    c_factor_.reset();
    throw NumericalError("saddle block C is not positive definite (CHOLMOD: breakdown at column " +
                         std::to_string(minor) + ")");
  }
}

Eigen::VectorXd QuadraticForm::apply(const Eigen::VectorXd& X) const {
  if (!qp_->saddle) return symmetric_times(qp_->S, X);  // threaded (linalg/parallel.hpp)
  const SaddleForm& f = *qp_->saddle;
  const Eigen::VectorXd Z = c_factor_->solve(f.B * X);  // Z = C⁻¹ B X
  return symmetric_times(f.A, X) + f.c * transpose_times(f.B, Z);
}

Eigen::VectorXd QuadraticForm::gradient(const Eigen::VectorXd& X) const {
  Eigen::VectorXd g = apply(X);
  const Eigen::VectorXd& r = qp_->r;
  const long n = g.size();
  // (entry by entry, so shared among the threads: the same bits as apply(X) − r)
#pragma omp parallel for schedule(static) if (2 * n >= kParallelWork)
  for (long i = 0; i < n; ++i) g[i] -= r[i];
  return g;
}

double QuadraticForm::objective(const Eigen::VectorXd& X) const {
  return 0.5 * X.dot(apply(X)) - qp_->r.dot(X);
}

}  // namespace cdyn
