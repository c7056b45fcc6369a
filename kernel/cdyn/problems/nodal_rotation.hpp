// nodal_rotation.hpp — node-local rotation of displacement pairs (u_x, u_y) to normal
// and tangential components, so that a nodal Signorini condition on an inclined plane,
//     n · u(a) ≤ gap(a),
// becomes a bound on one unknown of the step QP (qp/bound_qp.hpp; the QP itself is
// rotated by qp/rotated_qp.hpp).
//
// For each constrained node with unit normal n = (n_x, n_y) and tangent t = (−n_y, n_x),
// the unknowns (X_ix, X_iy) are replaced by X'_ix = n·u (normal) and X'_iy = t·u
// (tangential).  With R the orthogonal, block-diagonal matrix that is the identity
// except for the 2 × 2 blocks [n t] = [[n_x, −n_y], [n_y, n_x]] (X = R X'):
//     S' = Rᵀ S R,   r' = Rᵀ r              (saddle form: A' = Rᵀ A R, B' = B R, C, c)
//     min ½ X'ᵀS'X' − r'ᵀX'  is the same QP, and its bounds act on n·u and t·u;
//     X = R X',   λ = R λ'  (λ' = S'X' − r' = Rᵀ(S X − r)).
// R is orthogonal, so S' is SPD when S is, and its condition number is unchanged.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

struct NodalRotation {
  struct Node {
    int ix = -1, iy = -1;         // indices of u_x and u_y of the node in X
    double nx = 1.0, ny = 0.0;    // the normal (normalized by the functions below)
  };
  std::vector<Node> nodes;
};

// R (n × n), X = R X'.  InputError for an index out of range or used twice, or a zero normal.
SparseMatrix rotation_matrix(const NodalRotation& rotation, int n);

// v ↦ Rᵀ v (global → local components) and v ↦ R v (local → global).
Eigen::VectorXd to_local(const NodalRotation& rotation, const Eigen::VectorXd& v);
Eigen::VectorXd to_global(const NodalRotation& rotation, const Eigen::VectorXd& v);

}  // namespace cdyn
