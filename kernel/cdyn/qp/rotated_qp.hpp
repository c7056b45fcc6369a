// rotated_qp.hpp — the step QP (qp/bound_qp.hpp) in unknowns turned by an orthogonal
// change of basis X = R X' (Rᵀ R = I; e.g. the node-local normal/tangential rotation of
// problems/nodal_rotation.hpp, which makes a Signorini condition on an inclined plane a
// bound on one unknown):
//     S' = Rᵀ S R,  r' = Rᵀ r      (saddle form: A' = Rᵀ A R, B' = B R, C and c unchanged),
// the same QP, with the bounds acting on the rotated unknowns; its solution turns back by
//     X = R X',   λ = R λ'   (λ' = S'X' − r' = Rᵀ(S X − r)).
// R is orthogonal, so S' is SPD when S is, and its condition number is unchanged.
#pragma once

#include "cdyn/qp/bound_qp.hpp"

namespace cdyn {

// The QP in rotated unknowns.  lower and upper are copied unchanged: give them for the
// rotated unknowns.
BoundQP rotate(const BoundQP& qp, const SparseMatrix& R);

// A result of the rotated QP brought back: X = R X', λ = R λ'.  `active`, iterations and
// the KKT residual stay those of the rotated problem (the active indices name rotated
// unknowns).
QPResult rotate_back(const SparseMatrix& R, QPResult result);

}  // namespace cdyn
