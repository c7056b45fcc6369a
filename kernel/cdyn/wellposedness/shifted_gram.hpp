// shifted_gram.hpp — the inverse of G P Gᵀ − σ I (P the orthogonal projector onto
// Ker B) through one sparse Cholesky factorization, for the sparse check of condition (12).
//
// With K = [B; G] (B with linearly independent rows, N_H × N_W; G, N_g × N_W) and E the
// identity on the last N_g unknowns, the Gram matrix
//
//     M(σ) = K Kᵀ − σ E = [[B Bᵀ, B Gᵀ], [G Bᵀ, G Gᵀ − σ I]]
//
// has B Bᵀ (positive definite) as leading block and Schur complement
// G Gᵀ − σ I − G Bᵀ (B Bᵀ)⁻¹ B Gᵀ = G P Gᵀ − σ I.  Hence
//  - M(σ) is positive definite iff σ < λ_min(G P Gᵀ) = β² (condition 12): a successful
//    Cholesky factorization *certifies* that σ is below β², a failed one that it is not
//    (the inertia test of shift-and-invert eigensolvers, Grimes, Lewis & Simon, SIAM J.
//    Matrix Anal. Appl. 15 (1994), with Sylvester's law of inertia);
//  - M(σ) [μ; Q] = [0; q] solves (G P Gᵀ − σ I) Q = q, and W = Kᵀ [μ; Q] = Bᵀμ + GᵀQ
//    is P Gᵀ Q: B W = 0 is the first block row, and W − Gᵀ Q lies in the range of Bᵀ.
// This is the normal-equations form of the saddle system [[I, Bᵀ, Gᵀ], [B, 0, 0],
// [G, 0, σ I]]: half its size, symmetric positive definite (CHOLMOD's supernodal LLᵀ,
// its ordering analysed once for every σ), at the price of squaring the condition
// number of B, which is O(1) for these mass-type matrices with rows scaled to unit size.
// The squaring also costs half the digits of a small β if it were read from λ; β is
// therefore measured as |W| / |Q| (condition12_sparse.cpp), not as √λ.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

class ShiftedGram {
 public:
  // Builds M's pattern (lower triangle) and its fill-reducing ordering.  G may have no
  // rows: then M = B Bᵀ, whose factorization tests that B has independent rows.
  ShiftedGram(const SparseMatrix& B, const SparseMatrix& G);
  ~ShiftedGram();
  ShiftedGram(const ShiftedGram&) = delete;
  ShiftedGram& operator=(const ShiftedGram&) = delete;

  // Factorizes M(σ).  False when it is not positive definite (the factor is dropped).
  // Throws NumericalError when CHOLMOD fails otherwise (out of memory).
  bool factorize(double sigma);
  // CHOLMOD's rough reciprocal condition number of the last factor, (min L_ii / max L_ii)².
  double rcond() const;
  // (G P Gᵀ − σ I)⁻¹ q for the factorized σ; with W, also W = P Gᵀ of the result.
  Eigen::VectorXd solve(const Eigen::VectorXd& q, Eigen::VectorXd* W = nullptr) const;

  int factorizations() const;  // numeric factorizations so far (failed ones included)
  int solves() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cdyn
