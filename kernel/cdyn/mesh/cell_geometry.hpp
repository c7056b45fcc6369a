// mesh/cell_geometry.hpp — the affine map from the reference cell to a mesh cell.
//
//   x = a0 + J ξ,   J = [a1 − a0, …, a_d − a0]  (d = 1, 2, 3 columns),
// so ∫_K f dx = |det J| ∫_K̂ f∘F dξ and ∇_x φ = J⁻ᵀ ∇_ξ φ̂.  Only the leading d × d block
// of J and J⁻ᵀ is used; a 1D or 2D cell lives in the plane z = 0 (and y = 0 in 1D).
#pragma once

#include <array>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

struct CellGeometry {
  int dim = 2;
  Point a0;                  // first vertex
  double J[3][3] = {};       // Jacobian of the map (leading dim × dim block)
  double det = 0.0;          // det J (1D: the length); positive for valid cells
  double invJT[3][3] = {};   // J⁻ᵀ

  // The map of cell `cell`: J from its vertices, det J and J⁻ᵀ (no check of the sign;
  // Mesh::check refuses cells of non-positive measure).
  CellGeometry(const Mesh& mesh, int cell);

  // Physical point of reference point ξ.
  Point map(const RefPoint& xi) const;

  // Reference point of physical point x: ξ = J⁻¹ (x − a0).
  RefPoint reference(const Point& x) const;

  // Physical gradient J⁻ᵀ ĝ of a reference gradient ĝ (entries beyond dim are 0).
  std::array<double, 3> gradient(const std::array<double, 3>& ref_grad) const;
};

}  // namespace cdyn
