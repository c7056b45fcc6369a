// condition12_sparse.hpp — condition (12) of the seed without dense matrices:
//
//     β = inf_Q sup_{W ∈ Ker B} QᵀGW / (|Q||W|) = σ_min(G Z),   β² = λ_min(G P Gᵀ),  (12)
//
// P = Z Zᵀ the orthogonal projector onto Ker B (when N_g ≤ dim Ker B; β = 0 when
// dim Ker B < N_g, as in the dense check).
//
// Method (docs/semi_discretization.md, section 6):
//  1. rows of B scaled to unit max-norm, its rank and independent rows (row_basis.hpp:
//     a Cholesky certificate, SuiteSparseQR when B is rank deficient);
//  2. the Gram matrix M(σ) = [B; G][B; G]ᵀ − σ E, whose Schur complement is
//     G P Gᵀ − σ I (shifted_gram.hpp): one sparse Cholesky factorization per shift σ
//     both applies (G P Gᵀ − σ I)⁻¹ and certifies σ < β² (it succeeds iff so);
//  3. shift-and-invert Lanczos (lanczos.hpp) for the largest eigenvalue 1/(β² − σ) of
//     that inverse, the shift moved up toward β² after each run and certified by the
//     factorization (backed off when it fails).  The bottom of the spectrum of G P Gᵀ
//     is clustered (gaps O(h²) relative on the membrane), which a fixed shift cannot
//     resolve in few steps; a certified shift at a fraction of the gap below β² does;
//  4. β = |P Gᵀ Q| / |Q| for the final Ritz vector Q (unsquared, so that β = 0 comes
//     out at round-off, 1e-15, not at √ε).
// Cost: the factorizations of M (about N log N memory, N^1.5 time on 2D meshes) and a
// few tens of solves; measured figures in docs/performance.md.
#pragma once

#include "cdyn/base/sparse.hpp"

namespace cdyn {

struct WellPosedness;

// β of condition (12) for B (N_H × N_W) and G (N_g × N_W), the fields of WellPosedness
// as the dense check fills them (method = "sparse").  Throws NumericalError if a
// factorization fails (out of memory) or the eigensolver does not converge.
WellPosedness condition12_sparse(const SparseMatrix& B, const SparseMatrix& G);

}  // namespace cdyn
