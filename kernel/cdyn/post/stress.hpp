// post/stress.hpp — strain, stress and von Mises stress of a displacement field u_h of
// W^h (seed eqs. 1–2), in plane strain or in space, per cell and recovered at the
// vertices.
//
// In space ε(u) = ½(∇u + ∇uᵀ) and σ(u) = λ tr ε I + 2μ ε are full symmetric 3 × 3
// tensors.  Plane strain (docs/elasticity.md): u = (u_x(x, y), u_y(x, y), 0), so
//
//     ε(u) = ½(∇u + ∇uᵀ),         ε_zz = ε_xz = ε_yz = 0,
//     σ(u) = λ tr ε I + 2μ ε       (seed eq. 2, the 3D law),
//
// whose out-of-plane normal stress does not vanish: σ_zz = λ tr ε = λ(ε_xx + ε_yy)
// (= ν(σ_xx + σ_yy) with ν = λ / (2(λ + μ))), while σ_xz = σ_yz = 0.  The von Mises
// stress is that of this 3D tensor,
//
//     σ_vM = ( ½[(σ_xx − σ_yy)² + (σ_yy − σ_zz)² + (σ_zz − σ_xx)²] + 3 (σ_xy² + σ_xz² + σ_yz²) )^½,
//
// i.e. (3/2 s:s)^½ with s the deviator of the full 3 × 3 σ (σ_zz included, which is
// what makes it the plane-strain von Mises stress and not the plane-stress one).
//
// Per cell: the cell mean of ε(u_h), (1/|K|) ∫_K ε(u_h), and σ, σ_vM of that mean (σ is
// linear in ε, so σ_K is also the cell mean of σ; σ_vM is not linear, and is that of σ_K).
// For P1, ε(u_h) is constant on K and this is its value; for P2 it is affine and the
// mean is its value at the centroid; for P1+ the bubble's gradient has zero mean on K
// (∫_K ∇b = ∮_∂K b ν = 0, b vanishing on ∂K), so the cell means are those of the P1
// part.  The mean is computed with a rule exact for ∇u_h (degree deg(W) − 1).
//
// At the vertices: the area- (volume-) weighted average of the cell values around the vertex,
//     ε(a) = Σ_{K ∋ a} |K| ε_K / Σ_{K ∋ a} |K|   (and σ(a) alike; σ_vM(a) of σ(a)),
// which is the lumped-mass L² projection of the piecewise constant field onto P1 (the
// lumped P1 mass of vertex a is Σ_{K ∋ a} |K|/(d + 1)).  It reproduces a constant field
// exactly; across an interface between two materials it mixes the two sides (σν is
// continuous there, the tangential stress and ε are not): the cell values are the
// faithful ones at an interface.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "cdyn/fe/cell_coefficient.hpp"
#include "cdyn/fe/fe_space.hpp"

namespace cdyn {

// A symmetric 3 × 3 tensor (plane strain: xz = yz = 0).
struct SymmetricTensor {
  double xx = 0.0, yy = 0.0, zz = 0.0, xy = 0.0, xz = 0.0, yz = 0.0;
};

struct StressState {
  SymmetricTensor epsilon;  // ε (plane strain: zz = 0)
  SymmetricTensor sigma;    // σ = λ tr ε I + 2μ ε (plane strain: zz = λ tr ε)
  double von_mises = 0.0;   // σ_vM of sigma
};

// σ = λ tr ε I + 2μ ε (seed eq. 2).
SymmetricTensor isotropic_stress(const SymmetricTensor& epsilon, double lambda, double mu);

// σ_vM = (3/2 s:s)^½, s the deviator of σ.
double von_mises(const SymmetricTensor& sigma);

// The cell means of ε(u_h), σ and σ_vM on every cell, u_h given by its coefficients
// U_full on all dofs of W, with one component per coordinate of a 2D or 3D mesh
// (Dirichlet values included).  λ, μ:
// one number or one per cell (problems/elastic_contact.hpp's cell_materials).
std::vector<StressState> cell_stress(const FESpace& W, const Eigen::VectorXd& U_full, const CellCoefficient& lambda,
                                     const CellCoefficient& mu);

// The area- (volume-) weighted vertex averages of the cell values (one per vertex of `mesh`).
std::vector<StressState> vertex_stress(const Mesh& mesh, const std::vector<StressState>& cells);

}  // namespace cdyn
