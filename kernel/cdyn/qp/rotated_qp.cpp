// rotated_qp.cpp — the step QP in rotated unknowns; see rotated_qp.hpp.
#include "cdyn/qp/rotated_qp.hpp"

#include <string>

#include "cdyn/base/error.hpp"

namespace cdyn {

BoundQP rotate(const BoundQP& qp, const SparseMatrix& R) {
  const int n = qp.size();
  if (R.rows() != n || R.cols() != n)
    throw InputError("rotate: R is " + std::to_string(R.rows()) + "x" + std::to_string(R.cols()) + ", the QP has " +
                     std::to_string(n) + " unknowns");
  BoundQP out;
  if (qp.saddle) {
    SaddleForm f = *qp.saddle;
    f.A = SparseMatrix(R.transpose() * qp.saddle->A * R);
    f.B = SparseMatrix(qp.saddle->B * R);
    f.A.makeCompressed();
    f.B.makeCompressed();
    out.saddle = std::move(f);
  } else {
    out.S = SparseMatrix(R.transpose() * qp.S * R);
    out.S.makeCompressed();
  }
  out.r = R.transpose() * qp.r;
  out.lower = qp.lower;
  out.upper = qp.upper;
  return out;
}

QPResult rotate_back(const SparseMatrix& R, QPResult result) {
  result.X = R * result.X;
  result.reaction = R * result.reaction;
  return result;
}

}  // namespace cdyn
