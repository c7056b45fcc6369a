// row_basis.hpp — the rank of B and, when its rows are dependent, a subset of its rows
// spanning the same row space, for the sparse check of condition (12).
//
// Condition (12) (β = σ_min(G Z), Z an orthonormal basis of Ker B) needs dim Ker B =
// N_W − rank B, and the sparse method (condition12_sparse.hpp) needs B with linearly
// independent rows: it factorizes the Gram matrix [B; G][B; G]ᵀ, singular otherwise.
// Dropping dependent rows of B does not change Ker B.
//
// Method.  The common case is certified by one sparse Cholesky factorization (CHOLMOD)
// of the smaller Gram matrix, B Bᵀ when N_H ≤ N_W, Bᵀ B otherwise: it succeeds with
// pivots far from zero iff B has full row (column) rank.  Otherwise a rank-revealing
// sparse QR of Bᵀ (SuiteSparseQR: multifrontal Householder QR with Heath's column
// deflation, Davis, ACM TOMS 38 (2011)) gives the rank and the live columns of Bᵀ, i.e.
// independent rows of B.  The QR is the slower of the two (3–4× at 300k dofs), so it is
// only the fallback.
#pragma once

#include <vector>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

struct RowBasis {
  int rank = 0;
  // Indices of `rank` linearly independent rows of B.  Empty when rank = N_W < N_H
  // (Ker B = {0}: condition (12) needs no factorization then).
  std::vector<int> rows;
};

// B with every row divided by its largest magnitude (zero rows kept): the same kernel,
// rows of unit size whatever the local cell size, so that rank thresholds are relative.
SparseMatrix rows_scaled_to_unit_max(const SparseMatrix& B);

// B with its rows scaled to unit max-norm (rows_scaled_to_unit_max: the thresholds are
// relative to that).  Throws NumericalError if a factorization fails for want of memory.
RowBasis row_basis(const SparseMatrix& B);

}  // namespace cdyn
