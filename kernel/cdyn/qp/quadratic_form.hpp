// quadratic_form.hpp — X ↦ S X for either form of the step matrix (qp/bound_qp.hpp).
//
// In saddle form C is factorized (CHOLMOD) when set() sees a new C, and
//     S X = A X + c Bᵀ (C⁻¹ (B X))          (seed eq. 11, M = Bᵀ C⁻¹ B never formed).
#pragma once

#include <memory>

#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/qp/bound_qp.hpp"

namespace cdyn {

// A solver keeps one across calls; set() before use each time (it keeps a pointer to
// the problem).
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
  Eigen::VectorXd gradient(const Eigen::VectorXd& X) const;  // S X − r (the reaction λ at X)
  double objective(const Eigen::VectorXd& X) const;  // ½ Xᵀ S X − rᵀ X
  const Eigen::VectorXd& diagonal() const { return D_; }  // scaling_diagonal(qp), computed by set()

 private:
  const BoundQP* qp_ = nullptr;
  Eigen::VectorXd D_;
  SparseMatrix C_;
  std::unique_ptr<SparseCholesky> c_factor_;
};

}  // namespace cdyn
