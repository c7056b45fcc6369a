// cell_geometry.hpp — the affine map from the reference cell to a mesh cell.
//
//   x = a0 + J ξ,   J = [a1 − a0, a2 − a0]  (triangle)  or  J = a1 − a0  (interval),
// so ∫_K f dx = |det J| ∫_K̂ f∘F dξ and ∇_x φ = J⁻ᵀ ∇_ξ φ̂.
#pragma once

#include <array>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

struct CellGeometry {
  int dim = 2;
  Point a0;                  // first vertex
  double J[2][2] = {};       // Jacobian of the map (1D: J[0][0] only)
  double det = 0.0;          // det J (1D: the length); positive for valid cells
  double invJT[2][2] = {};   // J⁻ᵀ

  // The map of cell `cell`: J from its vertices, det J and J⁻ᵀ (no check of the sign;
  // Mesh::check refuses cells of non-positive measure).
  CellGeometry(const Mesh& mesh, int cell);

  // Physical point of reference point ξ.
  Point map(const std::array<double, 2>& xi) const;

  // Physical gradient J⁻ᵀ ĝ of a reference gradient ĝ.
  std::array<double, 2> gradient(const std::array<double, 2>& ref_grad) const;
};

}  // namespace cdyn
