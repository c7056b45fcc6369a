// row_basis.cpp — a Cholesky certificate of full rank, SuiteSparseQR when it fails.
#include "cdyn/wellposedness/row_basis.hpp"

#include <SuiteSparseQR.hpp>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "cdyn/base/error.hpp"
#include "cdyn/wellposedness/condition12.hpp"
#include "cdyn/wellposedness/shifted_gram.hpp"

namespace cdyn {

namespace {

// A Cholesky factor of the Gram matrix X Xᵀ (rows of X of unit max-norm) whose pivots
// are all above this fraction of the largest (in CHOLMOD's rcond, the squared ratio of
// the extreme diagonal entries of L) certifies independent rows.  The pivots are
// bounded below by λ_min(X Xᵀ), which is ≥ 0.04 on the membrane's pairs (the dense
// QR's smallest nonzero pivot, 0.21, squared), and an exact dependency leaves a pivot
// at round-off, 1e-16; 1e-12 is the squared kRankTolerance's neighbour that round-off
// of the squared matrix allows.
constexpr double kGramPivotTolerance = 1e-12;

bool independent_rows(const SparseMatrix& X) {
  ShiftedGram gram(X, SparseMatrix(0, X.cols()));
  return gram.factorize(0.0) && gram.rcond() > kGramPivotTolerance;
}

// Rank and live columns of A (here Bᵀ) from SuiteSparseQR's rank-revealing QR: A E = Q R
// with the `rank` live columns first in E.  Q is not kept.
RowBasis live_columns(const SparseMatrix& A) {
  cholmod_common cc;
  cholmod_l_start(&cc);
  cc.print = 0;
  // SPQR takes 64-bit indices.
  std::vector<SuiteSparse_long> p(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
  std::vector<SuiteSparse_long> i(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  cholmod_sparse a{};
  a.nrow = A.rows();
  a.ncol = A.cols();
  a.nzmax = A.nonZeros();
  a.p = p.data();
  a.i = i.data();
  a.x = const_cast<double*>(A.valuePtr());
  a.stype = 0;
  a.itype = CHOLMOD_LONG;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  // Columns whose remaining 2-norm falls below kRankTolerance times the largest column
  // norm are dead: the dense check's relative pivot threshold (condition12.hpp).
  double largest = 0.0;
  for (int j = 0; j < A.outerSize(); ++j) largest = std::max(largest, A.col(j).norm());
  cholmod_sparse* R = nullptr;
  SuiteSparse_long* E = nullptr;
  const SuiteSparse_long rank =
      SuiteSparseQR<double>(SPQR_ORDERING_DEFAULT, kRankTolerance * largest, 0, &a, &R, &E, &cc);
  const int status = cc.status;
  RowBasis basis;
  if (rank >= 0) {
    basis.rank = static_cast<int>(rank);
    basis.rows.resize(basis.rank);
    for (int k = 0; k < basis.rank; ++k) basis.rows[k] = E ? static_cast<int>(E[k]) : k;
    std::sort(basis.rows.begin(), basis.rows.end());
  }
  cholmod_l_free_sparse(&R, &cc);
  if (E) cholmod_l_free(A.cols(), sizeof(SuiteSparse_long), E, &cc);
  cholmod_l_finish(&cc);
  if (rank < 0)
    throw NumericalError("condition (12): the rank-revealing QR of B failed (SuiteSparseQR status " +
                         std::to_string(status) + (status == CHOLMOD_OUT_OF_MEMORY ? ", out of memory" : "") + ")");
  return basis;
}

}  // namespace

SparseMatrix rows_scaled_to_unit_max(const SparseMatrix& B) {
  Eigen::VectorXd largest = Eigen::VectorXd::Zero(B.rows());
  for (int j = 0; j < B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it)
      largest[it.row()] = std::max(largest[it.row()], std::abs(it.value()));
  SparseMatrix scaled = B;
  for (int j = 0; j < scaled.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(scaled, j); it; ++it)
      if (largest[it.row()] > 0.0) it.valueRef() /= largest[it.row()];
  return scaled;
}

RowBasis row_basis(const SparseMatrix& B) {
  const int nH = static_cast<int>(B.rows()), nW = static_cast<int>(B.cols());
  RowBasis basis;
  if (nH == 0 || nW == 0) return basis;
  if (nH <= nW && independent_rows(B)) {
    basis.rank = nH;
    basis.rows.resize(nH);
    std::iota(basis.rows.begin(), basis.rows.end(), 0);
    return basis;
  }
  if (nH > nW && independent_rows(B.transpose())) {
    basis.rank = nW;  // Ker B = {0}; which rows span is not needed
    return basis;
  }
  const SparseMatrix Bt = B.transpose();
  return live_columns(Bt);
}

}  // namespace cdyn
