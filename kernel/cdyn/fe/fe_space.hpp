// fe/fe_space.hpp — a finite element space on a mesh: its degrees of freedom (dof map).
//
// A space is a reference element (P0, P1, P1+, P2) repeated over the cells of a mesh,
// with `components` copies for vector-valued fields (2 for plane elasticity, 3 in 3D).  Both
// spaces of the seed's approximation (eq. 9) are FESpaces: W^h (displacement, basis φ_i)
// and H^h (velocity, basis ψ_i).
//
// Numbering of the scalar dofs (one scalar function per dof):
//   P1, P1+, P2 : vertex dofs first — scalar dof v IS vertex v — then one bubble per
//                 cell (P1+: dof n_vertices + c) or one dof per edge (P2, 2D and 3D) /
//                 per cell midpoint (P2, 1D);
//   P0          : dof c is cell c.
// Vector-valued spaces interleave the components node by node:
//   dof(scalar s, component k) = components * s + k,
// so the displacement components of a contact node are adjacent (a node-local
// rotation to normal/tangential components touches a 2 × 2 or 3 × 3 block).
//
// "Vertex dofs" are where constraints live (the seed's K̄^h acts on vertex values
// only, never on bubble or edge dofs).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <span>
#include <vector>

#include "cdyn/fe/element.hpp"
#include "cdyn/fe/field.hpp"
#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

class FESpace {
 public:
  // The space of `element` on `mesh` (kept by pointer: the mesh must outlive the space);
  // builds the dof map and the nodal points.  Throws InputError unless components is 1,
  // 2 or 3.
  FESpace(const Mesh& mesh, Element element, int components = 1);

  const Mesh& mesh() const { return *mesh_; }
  Element element() const { return element_; }
  int components() const { return components_; }
  int dim() const { return mesh_->dim; }

  int n_scalar_dofs() const { return n_scalar_dofs_; }
  int n_dofs() const { return components_ * n_scalar_dofs_; }
  int local_dofs() const { return local_dofs_; }             // scalar dofs per cell
  int degree() const { return polynomial_degree(element_, dim()); }

  // Scalar dofs of cell c, in local order (see fe/element.hpp).
  std::span<const int> cell_dofs(int c) const {
    return {cell_dofs_.data() + static_cast<std::size_t>(c) * local_dofs_, static_cast<std::size_t>(local_dofs_)};
  }

  // Global dof of scalar dof s, component k.
  int dof(int s, int k = 0) const { return components_ * s + k; }

  // Whether the space has one dof per vertex (all but P0).
  bool has_vertex_dofs() const { return element_ != Element::P0; }

  // The dof carrying the value at vertex v, component k (requires has_vertex_dofs()).
  int vertex_dof(int v, int k = 0) const { return dof(v, k); }

  // Nodal point of each scalar dof (vertex, edge midpoint, cell centroid).
  const std::vector<Point>& dof_points() const { return dof_points_; }

  // Scalar dofs attached to the boundary facets of the given parts: the facets'
  // vertices and, for P2, their edge dofs (sorted, unique).
  std::vector<int> boundary_scalar_dofs(const std::vector<int>& parts) const;

  // Nodal interpolant of a scalar field at time t (components must be 1): the seed's
  // u₀^h (eq. 9), the rate U̇⁰ from which C V⁰ = B U̇⁰ gives V⁰ (eq. 11), the Dirichlet
  // data.  For P1+
  // the bubble coefficient makes the interpolant exact at the centroid.
  Eigen::VectorXd interpolate(const Field& f, double t = 0.0) const;

  // Interpolant of a vector field given component by component.
  Eigen::VectorXd interpolate(const std::vector<Field>& f, double t = 0.0) const;

  // Value of component k of the finite element function U in cell c at reference ξ.
  double value_in_cell(const Eigen::VectorXd& U, int c, const RefPoint& xi, int k = 0) const;

 private:
  const Mesh* mesh_;
  Element element_;
  int components_;
  int local_dofs_;
  int n_scalar_dofs_ = 0;
  std::vector<int> cell_dofs_;        // n_cells × local_dofs
  std::vector<Point> dof_points_;
  std::vector<std::array<int, 2>> edges_;  // P2 in 2D and 3D: the vertices of each edge dof
};

}  // namespace cdyn
