// sparse.hpp — the sparse matrix type every stage shares, and the saddle form of a
// step matrix S = A + c Bᵀ C⁻¹ B (seed eq. 11).
//
// Matrices are Eigen's compressed sparse column (column pointers, row indices, values;
// int indices), the layout of the classic Fortran sparse solvers: they pass to CHOLMOD
// and UMFPACK as they are, without copies.
#pragma once

#include <Eigen/Sparse>

namespace cdyn {

using SparseMatrix = Eigen::SparseMatrix<double>;

// S = A + c Bᵀ C⁻¹ B given by its blocks: A (N_W × N_W, symmetric positive
// semidefinite), B (N_H × N_W), C (N_H × N_H, symmetric positive definite), c > 0 (a
// scheme's mass factor, e.g. 1/dt² for backward Euler).  The seed's mass M = Bᵀ C⁻¹ B
// (eq. 11) is dense when C⁻¹ is (a continuous velocity space H^h); this form never
// forms it: S X = A X + c Bᵀ (C⁻¹ (B X)), and S X = r is the sparse saddle system
//     [[A, c Bᵀ], [B, −C]] [X; Z] = [r; 0].
struct SaddleForm {
  SparseMatrix A, B, C;
  double c = 1.0;
};

// True when a and b are compressed with the same pattern (and, with values = true, the
// same values, bit for bit).
bool same_matrix(const SparseMatrix& a, const SparseMatrix& b, bool values = true);

}  // namespace cdyn
