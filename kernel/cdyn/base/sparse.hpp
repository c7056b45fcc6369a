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

// The saddle matrix with its second block row scaled by c, so that it is symmetric:
//     K = [[A, c Bᵀ], [c B, −c C]],   K [X; Z] = [r; 0]  ⇔  S X = r,  Z = C⁻¹ B X,
// with every diagonal entry stored (a held unknown's row becomes the identity's in K's
// pattern).  Symmetric indefinite: N_W positive and N_H negative eigenvalues when S and
// C are positive definite (Sylvester's law on its block LDLᵀ).
SparseMatrix symmetric_saddle_matrix(const SaddleForm& f);

}  // namespace cdyn
