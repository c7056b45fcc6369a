// fe/quadrature.hpp — quadrature rules on the reference interval, triangle and
// tetrahedron.
//
// Reference cells: the interval [0, 1], the triangle with vertices (0,0), (1,0), (0,1)
// and the tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1).  A rule of degree p
// integrates every polynomial of total degree <= p exactly (up to round-off); its
// weights sum to the reference measure (1, 1/2, resp. 1/6).
//
// They compute every integral of the seed's matrices A, B, C and L (eq. 10).
//
// Why these rules: the assembly needs products as high as a bubble times a bubble —
// (λ1λ2λ3)², degree 6, on triangles; (λ1λ2λ3λ4)², degree 8, on tetrahedra — and the
// error norms need more.  Instead of tables of special rules:
//  - on the interval, Gauss–Legendre rules (nodes from the Golub–Welsch eigenvalue
//    problem, exact to round-off for any degree);
//  - on the triangle, their collapsed (Duffy) product: (s, t) in [0,1]² -> (ξ, η) =
//    (s(1 − t), t), Jacobian 1 − t;
//  - on the tetrahedron, the Grundmann–Möller rules (A. Grundmann, H. M. Möller,
//    "Invariant integration formulas for the n-simplex by combinatorial methods",
//    SIAM J. Numer. Anal. 15 (1978) 282–290): for every odd degree 2s + 1 a
//    closed formula, symmetric under the permutations of the vertices, with all points
//    inside the cell and C(s + 4, 4) of them (1, 5, 15, 35, 70 for s = 0..4: 70 for the
//    degree 8 of the bubble mass, where a collapsed product needs 150).  Some weights
//    are negative; the sum of their absolute values is 25 times the volume at s = 4,
//    which costs about one decimal digit of round-off and nothing else (the bubble's
//    mass 7.7e-15 relative; tests/unit/test_quadrature.cpp).
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

// The Grundmann–Möller rule of degree 2s + 1 on the reference tetrahedron.
QuadratureRule grundmann_moller(int s);

// Rule of the given polynomial degree on the reference cell of dimension dim (1, 2 or 3).
QuadratureRule cell_quadrature(int dim, int degree);

}  // namespace cdyn
