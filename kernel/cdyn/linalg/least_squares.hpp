// linalg/least_squares.hpp — x minimizing ‖K x − b‖₂ for a sparse K of any shape or rank
// (used for the initial acceleration, M Ü⁰ = L − A U⁰ of eq. 16 with a singular M).
//
// The schemes need it once per run, to start from an acceleration when the mass is
// singular (Newmark's A⁰ with Bᵀ A⁰ = L − A U⁰, docs/schemes.md): the equation is
// solvable only when the massless modes start in equilibrium, otherwise its least
// squares solution is the natural choice.  SuiteSparseQR (rank-revealing multifrontal
// QR) computes a basic least squares solution; no normal equations are formed, so the
// conditioning is that of K, not of KᵀK.
#pragma once

#include <Eigen/Core>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

// Throws NumericalError if the factorization fails.
Eigen::VectorXd least_squares(const SparseMatrix& K, const Eigen::VectorXd& b);

// Whether K has full column rank (Ker K = {0}): the numerical rank of the same QR, with
// SuiteSparseQR's default threshold (20 (m + n) ε times the largest column norm).
bool full_column_rank(const SparseMatrix& K);

}  // namespace cdyn
