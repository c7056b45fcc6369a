// nodal_rotation.hpp — node-local rotation of a node's displacement components to normal
// and tangential ones, so that a nodal Signorini condition on an inclined plane,
//     n · u(a) ≤ gap(a),
// becomes a bound on one unknown of the step QP (qp/bound_qp.hpp; the QP itself is
// rotated by qp/rotated_qp.hpp).
//
// In the plane, a constrained node with unit normal n = (n_x, n_y) and tangent
// t = (−n_y, n_x) has its unknowns (X_ix, X_iy) replaced by X'_ix = n·u (normal) and
// X'_iy = t·u (tangential): R is the identity except for the 2 × 2 blocks [n t].  In
// space, (X_ix, X_iy, X_iz) become (n·u, t₁·u, t₂·u) with the orthonormal frame
// [n t₁ t₂] of Duff et al., "Building an orthonormal basis, revisited" (JCGT 6, 2017):
// continuous in n except across n_z = 0's sign change, and with no square root beyond
// n's normalization.  With X = R X':
//     S' = Rᵀ S R,   r' = Rᵀ r              (saddle form: A' = Rᵀ A R, B' = B R, C, c)
//     min ½ X'ᵀS'X' − r'ᵀX'  is the same QP, and its bounds act on n·u and t·u;
//     X = R X',   λ = R λ'  (λ' = S'X' − r' = Rᵀ(S X − r)).
// R is orthogonal, so S' is SPD when S is, and its condition number is unchanged.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

struct NodalRotation {
  struct Node {
    int ix = -1, iy = -1;         // indices of u_x and u_y of the node in X
    double nx = 1.0, ny = 0.0;    // the normal (normalized by the functions below)
    int iz = -1;                  // index of u_z (a node in space), −1 in the plane
    double nz = 0.0;
  };
  std::vector<Node> nodes;
};

// The columns [n t] (plane) or [n t₁ t₂] (space) of a node's block, n normalized.
// InputError for a zero or non-finite normal.
std::array<std::array<double, 3>, 3> rotation_frame(const NodalRotation::Node& node);

// R (n × n), X = R X'.  InputError for an index out of range or used twice, or a zero normal.
SparseMatrix rotation_matrix(const NodalRotation& rotation, int n);

// v ↦ Rᵀ v (global → local components) and v ↦ R v (local → global).
Eigen::VectorXd to_local(const NodalRotation& rotation, const Eigen::VectorXd& v);
Eigen::VectorXd to_global(const NodalRotation& rotation, const Eigen::VectorXd& v);

}  // namespace cdyn
