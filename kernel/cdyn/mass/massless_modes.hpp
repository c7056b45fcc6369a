// massless_modes.hpp — a sparse basis of the massless displacements F = Ker B (seed,
// "Sufficient condition for the well-posedness"), in the local form the full-step
// reconstruction of eq. (14) needs.
//
// With M = Bᵀ C⁻¹ B the inertia sees a displacement only through B W.  The rest,
// Ker B, carries no inertia: the seed's Theorem 1 splits U = U_F + U_{F^c} and finds
// U_F from U_{F^c} by the static problem (14).  To solve (14) as a bound-constrained QP
// the directions of Ker B are written W = U + Z d with
//     B Z = 0,   Z(pinned[k], k) = 1 and Z(pinned[j], k) = 0 for j ≠ k,
// so that the unknown pinned[k] of W is U's plus d_k, and a bound on a pinned unknown is
// a bound on d_k.  Every constrained unknown must be pinned (else (14) could not move
// it); condition (12) is then the statement that the bounds act independently on d.
//
// Two local forms are recognised from B alone (B: N_H × n, the velocity rows and the
// free displacement columns; for a classical mass B is the saddle factor B_s of
// mass/classical.hpp):
//  - zero columns: the unknown is massless by itself (the redistributed mass: its
//    contact dofs, Khenous–Laborde–Renard) — Z's column is e_j;
//  - private columns: each row r of B has an unbounded unknown p(r) that appears in no
//    other row (the bubble of P1+/P0: B_K,b = ∫_K b; of several, the last: the bubble,
//    not a vertex of that one cell only), so B W = B U fixes W_p(r) from the
//    other unknowns of row r; every other unknown j is pinned with
//        Z e_k = e_j − Σ_r (B_rj / B_r,p(r)) e_p(r).
// What remains after removing the zero columns must then have no kernel left (full
// column rank: checked by a rank-revealing QR) or be covered by private columns.
// Otherwise (e.g. P2/P1, whose Ker B has no local basis) there is no such form.
#pragma once

#include <optional>
#include <vector>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

struct MasslessModes {
  SparseMatrix Z;           // n × m, B Z = 0 (m = 0: Ker B = {0})
  std::vector<int> pinned;  // m unknowns, Z's rows there are the unit vectors
};

// The local basis of Ker B, or nothing when B has neither form above.  bounded[j] != 0
// marks the unknowns that carry a bound (they may not be eliminated).
std::optional<MasslessModes> massless_modes(const SparseMatrix& B, const std::vector<char>& bounded);

}  // namespace cdyn
