// nodal_rotation.cpp — node-local normal/tangential rotation; see nodal_rotation.hpp.
#include "cdyn/problems/nodal_rotation.hpp"

#include <cmath>
#include <string>

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

// The node's unknowns: 2 in the plane, 3 in space.
int size(const NodalRotation::Node& node) { return node.iz >= 0 ? 3 : 2; }
std::array<int, 3> indices(const NodalRotation::Node& node) { return {node.ix, node.iy, node.iz}; }

// Applies the blocks to v: transpose = false gives R v, true gives Rᵀ v.
Eigen::VectorXd apply_blocks(const NodalRotation& rotation, const Eigen::VectorXd& v, bool transpose) {
  Eigen::VectorXd w = v;
  for (const auto& node : rotation.nodes) {
    const auto F = rotation_frame(node);  // F[c] = column c of the block
    const auto i = indices(node);
    const int m = size(node);
    for (int r = 0; r < m; ++r) {
      double s = 0.0;
      for (int c = 0; c < m; ++c) s += transpose ? F[r][c] * v[i[c]] : F[c][r] * v[i[c]];
      w[i[r]] = s;
    }
  }
  return w;
}

}  // namespace

std::array<std::array<double, 3>, 3> rotation_frame(const NodalRotation::Node& node) {
  const bool space = node.iz >= 0;
  const double norm = space ? std::hypot(node.nx, node.ny, node.nz) : std::hypot(node.nx, node.ny);
  if (!(norm > 0) || !std::isfinite(norm))
    throw InputError("NodalRotation: node (" + std::to_string(node.ix) + ", " + std::to_string(node.iy) +
                     ") has a zero or non-finite normal");
  const double x = node.nx / norm, y = node.ny / norm;
  if (!space) return {{{x, y, 0.0}, {-y, x, 0.0}, {0.0, 0.0, 1.0}}};
  const double z = node.nz / norm;
  // Duff et al. (2017), listing 3: t₁, t₂ orthonormal and orthogonal to n for every unit n.
  const double sign = std::copysign(1.0, z);
  const double a = -1.0 / (sign + z), b = x * y * a;
  return {{{x, y, z}, {1.0 + sign * x * x * a, sign * b, -sign * x}, {b, sign + y * y * a, -y}}};
}

SparseMatrix rotation_matrix(const NodalRotation& rotation, int n) {
  std::vector<char> used(n, 0);
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& node : rotation.nodes) {
    const auto i = indices(node);
    const int m = size(node);
    for (int k = 0; k < m; ++k) {
      if (i[k] < 0 || i[k] >= n) throw InputError("NodalRotation: index " + std::to_string(i[k]) + " is out of range");
      if (used[i[k]]) throw InputError("NodalRotation: unknown " + std::to_string(i[k]) + " belongs to two nodes");
      used[i[k]] = 1;
    }
    const auto F = rotation_frame(node);
    for (int c = 0; c < m; ++c)
      for (int r = 0; r < m; ++r) t.emplace_back(i[r], i[c], F[c][r]);
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
