// redistribution.hpp — the redistribution operator T of the "redistributed" mass
// model (Khenous–Laborde–Renard 2008; seed slide "Mass Redistribution Method"):
//
//     M_red = Tᵀ M_ff T,
//
// T (n_free × n_free) the identity on every free dof except the contact dofs c, whose
// row replaces the value u_c by an affine extrapolation from nearby non-contact dofs
// of the same component:
//
//     (T U)_c = Σ_j w_cj U_j,   Σ_j w_cj p(a_j) = p(a_c)  for p ∈ {1, x, y}  (1D: {1, x}).
//
// Consequences (docs/semi_discretization.md, "Mass redistribution"):
//  - column c of T is zero, so M_red e_c = 0: no inertia on the contact dofs, and
//    N_iᵀ M_red N_j = 0 for contact i, j;
//  - T P = P for every interpolated affine field P (vertex, edge and hierarchical bubble
//    coefficients of an affine field are nodal values or 0), so Pᵀ M_red Q = Pᵀ M_ff Q
//    for all affine P, Q: total mass, centre of mass and second moments unchanged;
//  - T is injective on the non-contact dofs and M_ff is positive definite, so
//    Ker M_red = span{e_c} exactly, and M_red is symmetric positive semi-definite.
//
// Donors: the vertices met by a breadth-first walk over the cell adjacency from the
// contact vertex, ring by ring, whose dof of the same component is free and not a
// contact dof; the walk stops at the first ring where the donors found so far are
// affinely independent (span an affine function: dim + 1 of them not on one line in
// 2D, not in one plane in 3D).
// The weights are the minimum-norm solution of the dim + 1 moment equations.
#pragma once

#include <vector>

#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"

namespace cdyn {

// T for the given contact dofs (indices among bc's free dofs; vertex dofs only).
// Throws InputError if a contact dof is not a free vertex dof, or if no affinely
// independent donors are found within a few rings (e.g. every free vertex in contact).
SparseMatrix redistribution_operator(const FESpace& W, const DirichletLift& bc,
                                     const std::vector<int>& contact_free_dofs);

}  // namespace cdyn
