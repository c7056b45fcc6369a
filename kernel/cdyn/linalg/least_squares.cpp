// linalg/least_squares.cpp — SuiteSparseQR through Eigen's SPQR wrapper.
#include "cdyn/linalg/least_squares.hpp"

#include <Eigen/SPQRSupport>

#include "cdyn/base/error.hpp"

namespace cdyn {

Eigen::VectorXd least_squares(const SparseMatrix& K, const Eigen::VectorXd& b) {
  if (K.rows() != b.size()) throw InputError("least squares: K and b have different numbers of rows");
  Eigen::SPQR<SparseMatrix> qr(K);
  if (qr.info() != Eigen::Success) throw NumericalError("least squares: the QR factorization failed");
  Eigen::VectorXd x = qr.solve(b);
  if (qr.info() != Eigen::Success || !x.allFinite()) throw NumericalError("least squares: the QR solve failed");
  return x;
}

bool full_column_rank(const SparseMatrix& K) {
  if (K.rows() < K.cols()) return false;
  Eigen::SPQR<SparseMatrix> qr(K);
  if (qr.info() != Eigen::Success) throw NumericalError("rank: the QR factorization failed");
  return qr.rank() == K.cols();
}

}  // namespace cdyn
