// fe/quadrature.hpp — quadrature rules on the reference interval and triangle.
//
// Reference cells: the interval [0, 1] and the triangle with vertices (0,0), (1,0),
// (0,1).  A rule of degree p integrates every polynomial of total degree <= p exactly
// (up to round-off); its weights sum to the reference measure (1, resp. 1/2).
//
// They compute every integral of the seed's matrices A, B, C and L (eq. 10).
//
// Why these rules: the assembly needs, on triangles, products as high as a bubble
// times a bubble (λ1λ2λ3)² — degree 6 — and the error norms need more.  Instead of a
// table of special rules we use Gauss–Legendre rules (nodes from the Golub–Welsch
// eigenvalue problem, exact to round-off for any degree) and, on the triangle, their
// collapsed (Duffy) product: (s, t) in [0,1]² -> (ξ, η) = (s(1 − t), t), Jacobian 1 − t.
#pragma once

#include <array>
#include <vector>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

struct QuadratureRule {
  std::vector<RefPoint> points;  // reference coordinates (ξ, η, ζ); those beyond the dimension 0
  std::vector<double> weights;
  int size() const { return static_cast<int>(weights.size()); }
};

// n-point Gauss–Legendre rule on [0, 1]: exact for degree 2n − 1.
QuadratureRule gauss_legendre(int n);

// Rule of the given polynomial degree on the reference cell of dimension dim (1 or 2).
QuadratureRule cell_quadrature(int dim, int degree);

}  // namespace cdyn
