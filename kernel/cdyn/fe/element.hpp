// fe/element.hpp — the reference finite elements P0, P1, P1+ and P2 on intervals,
// triangles and tetrahedra: their local basis functions and reference gradients.
//
// Everything is written in barycentric coordinates of the reference cell:
//   tetrahedron  λ0 = 1 − ξ − η − ζ, λ1 = ξ, λ2 = η, λ3 = ζ;
//   triangle     λ0 = 1 − ξ − η, λ1 = ξ, λ2 = η;     interval  λ0 = 1 − ξ, λ1 = ξ.
// Local dof order: the vertex functions first (local vertex k is dof k), then
//   P1+ : the bubble b = 256 λ0λ1λ2λ3 (tetrahedron), 27 λ0λ1λ2 (triangle) or 4 λ0λ1
//         (interval), equal to 1 at the centroid.  The space is P1 ⊕ span{b} with the
//         P1 hat functions unchanged (a hierarchical basis: the vertex coefficients are
//         the vertex values, which is what the constraints u(a_i) ≥ g(a_i) act on);
//   P2  : vertex functions λi(2λi − 1), then the edge functions 4 λiλj for the edges
//         of local_edge() (the triangle's three, then on the tetrahedron (0,3), (1,3),
//         (2,3)) or the midpoint (interval);
//   P0  : the constant 1 (one dof, attached to the cell).
// The seed's pair for the membrane ("A model problem") is W^h = P1+ with H^h = P0; its
// slides call φ_T a "quadratic bubble", which is the 1D case (4λ0λ1); the bubble that
// vanishes on the boundary of a d-simplex is the product of its d + 1 barycentric
// coordinates, cubic on triangles and quartic on tetrahedra.
#pragma once

#include <array>
#include <string>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

enum class Element { P0, P1, P1Bubble, P2 };

// "P0", "P1", "P1+", "P2".
std::string to_string(Element e);

// Parses "P0", "P1", "P1+" (also "P1b", FreeFEM's name), "P2"; throws InputError.
Element element_from_string(const std::string& name);

// Number of local (scalar) basis functions on a cell of dimension dim.
int local_dofs(Element e, int dim);

// Polynomial degree of the local space (a bubble raises P1+ to dim + 1).
int polynomial_degree(Element e, int dim);

// Whether the element is continuous across cells (all but P0).
inline bool is_continuous(Element e) { return e != Element::P0; }

// The local basis at reference point xi: values[k] = φ_k(xi).
void shape_values(Element e, int dim, const RefPoint& xi, double* values);

// Reference gradients: grads[k] = ∇_ξ φ_k(xi) (entries beyond dim are 0).
void shape_gradients(Element e, int dim, const RefPoint& xi, std::array<double, 3>* grads);

// The nodal point of local dof k in reference coordinates (vertex, edge midpoint,
// centroid for the bubble and for P0).
RefPoint local_node(Element e, int dim, int k);

// Edges of the reference simplex: 3 on the triangle, 6 on the tetrahedron (1D: none).
int n_local_edges(int dim);

// The local vertices of edge k, in the order of the P2 edge dofs: (0,1), (1,2), (2,0),
// then (0,3), (1,3), (2,3) on the tetrahedron.
std::array<int, 2> local_edge(int k);

// Largest number of local dofs of any element (P2 on tetrahedra): a bound for arrays.
inline constexpr int kMaxLocalDofs = 10;

}  // namespace cdyn
