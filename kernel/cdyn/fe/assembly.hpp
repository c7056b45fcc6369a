// fe/assembly.hpp — the matrices and vectors of the seed's semi-discretization (eq. 10):
//
//   A_ij = a(φ_i, φ_j)    stiffness: the Laplacian ∫∇φ_i·∇φ_j, or linear (plane-strain
//                         in 2D) elasticity ∫ λ div φ_i div φ_j + 2μ ε(φ_i):ε(φ_j)
//                         (λ, μ constant per cell: fe/cell_coefficient.hpp)
//   B_ij = ∫ ψ_i φ_j      mixed mass, rows in H^h (velocity), columns in W^h
//   C_ij = ∫ ψ_i ψ_j      mass of H^h  (= assemble_mass(H, H))
//   L_i  = l(φ_i) = ∫ f φ_i
//
// All integrals use a quadrature rule exact for the polynomial integrand
// (fe/quadrature.hpp), e.g. degree 6 for the mass of the P1+ bubble on triangles, 8 on
// tetrahedra.
// Matrices are Eigen column-major sparse matrices (plain CSC), as CHOLMOD and
// UMFPACK take them.  Dof numbering is the spaces' (fe/fe_space.hpp); vector-valued
// spaces give block matrices with the components interleaved.
#pragma once

#include <functional>

#include <Eigen/Sparse>

#include "cdyn/fe/cell_coefficient.hpp"
#include "cdyn/fe/fe_space.hpp"

namespace cdyn {

using SparseMatrix = Eigen::SparseMatrix<double>;

// B_ij = ∫ ψ_i · φ_j, ψ_i in `rows`, φ_j in `cols` (same mesh, same number of
// components; componentwise product for vector spaces).  C = assemble_mass(H, H).
SparseMatrix assemble_mass(const FESpace& rows, const FESpace& cols);

// The same weighted by a coefficient constant per cell, ∫ ρ ψ_i · φ_j (the density of
// seed eq. 1).  A uniform ρ gives exactly ρ · assemble_mass(rows, cols) — the product
// taken after the sum, as every single-material result was computed; a per-cell ρ
// scales each cell's local matrix before it is summed.
SparseMatrix assemble_mass(const FESpace& rows, const FESpace& cols, const CellCoefficient& rho);

// A_ij = ∫ ∇φ_i · ∇φ_j on a scalar space (scale by E or c² outside).
SparseMatrix assemble_laplace(const FESpace& W);

// Linear elasticity on a d-component space of a d-dimensional mesh (d = 2: plane
// strain; d = 3): A_ij = ∫ λ div φ_i div φ_j + 2μ ε(φ_i) : ε(φ_j), λ and μ constant on
// each cell (one number each for a single material).
SparseMatrix assemble_elasticity(const FESpace& W, const CellCoefficient& lambda, const CellCoefficient& mu);

// L_i = ∫ f(x, y, t) φ_i, one field per component of W.  The rule has degree
// 2·deg(W) + 2 so that the quadrature error is below the discretization error of
// smooth data.
Eigen::VectorXd assemble_load(const FESpace& W, const std::vector<Field>& f, double t = 0.0);
Eigen::VectorXd assemble_load(const FESpace& W, const Field& f, double t = 0.0);

// t ↦ assemble_load(W, f, t), for a problem whose load is asked at every step.  When f
// depends on t and every component is uniform in space (an expression without x, y, z,
// such as "-0.6 + 3*sin(60*t)"), L(t) = Σ_k f_k(t) ∫ φ_{i,k}: the integrals of a unit
// load in each component are assembled once and each call is one evaluation of each f_k
// and a combination of vectors (the same quadrature; round-off aside, the same vector).
// Otherwise every call assembles (a load constant in t is assembled once by its user).
// W must outlive the returned function.
std::function<Eigen::VectorXd(double)> load_in_time(const FESpace& W, std::vector<Field> f, bool depends_on_time);

// L_i = ∫ w f(x, y, t) · φ_i with a weight constant per cell, e.g. the weight ρ g of a
// body of several densities under gravity g (f = g, w = ρ).  Same rule as above.
Eigen::VectorXd assemble_load(const FESpace& W, const CellCoefficient& w, const std::vector<Field>& f, double t = 0.0);

// Boundary load (the Neumann term of l, seed eq. 3): L_i = ∫_{Γ_N} g(x, t) · φ_i ds
// over the boundary facets of the given parts (indices into mesh.part_names), one field
// per component of W (fe/boundary_load.cpp).  Each facet — an edge in 2D, a triangle in
// 3D — is integrated as a facet of its cell, with the cell's basis (so every element is
// handled alike; bubbles vanish there); 1D facets are points, where ∫ g φ_i ds is the
// value g φ_i.  Rules of degree 2·deg(W) + 2 on the facet, as assemble_load.
Eigen::VectorXd assemble_boundary_load(const FESpace& W, const std::vector<int>& parts, const std::vector<Field>& g,
                                       double t = 0.0);

}  // namespace cdyn
