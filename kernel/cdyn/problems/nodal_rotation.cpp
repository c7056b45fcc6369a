// nodal_rotation.cpp — node-local normal/tangential rotation; see nodal_rotation.hpp.
#include "cdyn/problems/nodal_rotation.hpp"

#include <cmath>
#include <string>

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

// The unit normal of a node, checked.
std::pair<double, double> unit_normal(const NodalRotation::Node& node) {
  const double norm = std::hypot(node.nx, node.ny);
  if (!(norm > 0) || !std::isfinite(norm))
    throw InputError("NodalRotation: node (" + std::to_string(node.ix) + ", " + std::to_string(node.iy) +
                     ") has a zero or non-finite normal");
  return {node.nx / norm, node.ny / norm};
}

// Applies the 2 × 2 blocks to v: transpose = false gives R v, true gives Rᵀ v.
Eigen::VectorXd apply_blocks(const NodalRotation& rotation, const Eigen::VectorXd& v, bool transpose) {
  Eigen::VectorXd w = v;
  for (const auto& node : rotation.nodes) {
    const auto [nx, ny] = unit_normal(node);
    const double a = v[node.ix], b = v[node.iy];
    if (transpose) {  // (n·v, t·v)
      w[node.ix] = nx * a + ny * b;
      w[node.iy] = -ny * a + nx * b;
    } else {  // a n + b t
      w[node.ix] = nx * a - ny * b;
      w[node.iy] = ny * a + nx * b;
    }
  }
  return w;
}

}  // namespace

SparseMatrix rotation_matrix(const NodalRotation& rotation, int n) {
  std::vector<char> used(n, 0);
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& node : rotation.nodes) {
    for (int i : {node.ix, node.iy}) {
      if (i < 0 || i >= n) throw InputError("NodalRotation: index " + std::to_string(i) + " is out of range");
      if (used[i]) throw InputError("NodalRotation: unknown " + std::to_string(i) + " belongs to two nodes");
      used[i] = 1;
    }
    const auto [nx, ny] = unit_normal(node);
    t.emplace_back(node.ix, node.ix, nx);
    t.emplace_back(node.iy, node.ix, ny);
    t.emplace_back(node.ix, node.iy, -ny);
    t.emplace_back(node.iy, node.iy, nx);
  }
  for (int i = 0; i < n; ++i)
    if (!used[i]) t.emplace_back(i, i, 1.0);
  SparseMatrix R(n, n);
  R.setFromTriplets(t.begin(), t.end());
  R.makeCompressed();
  return R;
}

Eigen::VectorXd to_local(const NodalRotation& rotation, const Eigen::VectorXd& v) {
  return apply_blocks(rotation, v, true);
}

Eigen::VectorXd to_global(const NodalRotation& rotation, const Eigen::VectorXd& v) {
  return apply_blocks(rotation, v, false);
}

}  // namespace cdyn
