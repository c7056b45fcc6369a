// condition12.hpp — condition (12) of the seed: the constraints must act
// independently on the inertia-free displacements F = Ker B,
//
//     β = inf_{Q ∈ R^{N_g}} sup_{W ∈ F} QᵀGW / (|Q||W|) = σ_min(G Z)  > 0,        (12)
//
// Z an orthonormal basis of Ker B (B with the free columns of W^h), G (N_g × N_W) the
// constraint rows (G = −I on the constrained vertex dofs for the obstacle u(a_i) ≥ g;
// the nodal normals N_iᵀ for Signorini contact).  β = 0 whenever dim Ker B < N_g.
// For a classical mass model Ker B is Ker M (consistent: {0}; redistributed: the
// contact dofs).  With (12), Theorem 1 gives a unique Lipschitz solution and Theorem 2
// energy conservation.
//
// Two methods compute it (docs/semi_discretization.md, section 6):
//  - dense (this file), the reference: a column-pivoted Householder QR of (D B)ᵀ,
//    D = diag(1/max_j |B_ij|) (a row scaling, Ker unchanged), gives the rank r of B and
//    an orthogonal Q = [Q_r, Z]; Zᵀ Gᵀ is the last N_W − r rows of Qᵀ Gᵀ (the
//    reflections applied to the N_g columns of Gᵀ, Z never formed), and β its smallest
//    singular value.  Cost O(N_W N_H (N_H + N_g)), memory N_W × N_H doubles: refused
//    above kWellposednessDenseLimit free dofs;
//  - sparse (condition12_sparse.hpp): β² = λ_min(G P Gᵀ) by certified shift-and-invert
//    Lanczos on sparse Cholesky factorizations of the Gram matrix of [B; G]; any size
//    that fits in memory (1M dofs in about a minute).
// condition12() picks the dense method up to kCondition12DenseUpTo dofs, where it is the
// faster one, and the sparse one above.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/mass/mass_spec.hpp"

namespace cdyn {

// Largest N_W (or N_H) the dense check accepts.  Measured (Release, one core of this
// machine): membrane n = 20, P1+/P0 (N_W = 1161) 0.6 s, P2/P1 (1521) 0.4 s; n = 25,
// P1+/P0 (1826) 2.6 s; the QR costs ~N_W N_H², so 3000 is about 10–15 s.
inline constexpr int kWellposednessDenseLimit = 3000;

// Largest max(N_W, N_H) for which condition12() uses the dense method by default.
// Measured (Release, one core, best of 7) on the membrane for P1+/P0, P1+/P1, P2/P1 and
// P2/P0: the dense method is faster up to N_W ≈ 100 (0.4 ms against 0.6 ms at n = 6),
// the sparse one from N_W ≈ 180 on (1.7 ms against 2.3 ms at n = 8; 5–10× at N_W ≈ 600).
// Both take under a millisecond at the crossover, so the choice matters for speed only
// above it, where the dense cost grows like N_W³.
inline constexpr int kCondition12DenseUpTo = 150;

enum class Condition12Method { automatic, dense, sparse };

// β at or below this counts as 0.  When G Z is exactly rank deficient the computed β
// is round-off: exactly 0 from BDCSVD's deflation, 3e-16 .. 4e-16 with JacobiSVD
// (P1+/P1 with the full P1 velocity space, n = 10, 20); the pairs that satisfy (12)
// measure β ≥ 0.09 on the seed's meshes (docs/semi_discretization.md).  1e-8 (≈ √ε)
// sits 8 decades above the first and 7 below the second.
inline constexpr double kBetaTolerance = 1e-8;

// Relative threshold on the QR pivots |R_ii| / |R_00| of the row-scaled Bᵀ below which
// B is rank deficient.  Measured on the membrane (n = 10, 20, every pair): the nonzero
// pivots are ≥ 0.21, the zero ones (P2/P0, whose B has a one-dimensional defect on the
// structured mesh) ≤ 7e-15; 1e-9 is far from both, and stays far for meshes graded by
// several orders of magnitude since the rows are scaled to unit size.
inline constexpr double kRankTolerance = 1e-9;

struct WellPosedness {
  std::string pair;      // "P1+/P0", "consistent", ...
  int n_W = 0;           // free dofs of W^h
  int n_H = 0;           // velocity dofs (free dofs of W^h for a classical model)
  int dim_ker_B = 0;     // dim F = dim Ker B
  int n_g = 0;           // constraints
  double beta = 0.0;     // σ_min(G Z); +infinity when there is no constraint
  bool satisfied = false;  // β > kBetaTolerance
  std::string method;      // "dense" or "sparse"
  int factorizations = 0;  // sparse method: Cholesky factorizations of the shifted Gram matrix
  int solves = 0;          // sparse method: solves with them
};

// Condition (12) for the given B (rows H^h, columns the free dofs of W^h) and G
// (N_g × N_W), by `method` (automatic: dense up to kCondition12DenseUpTo dofs).  The
// dense method throws InputError above `dense_limit`; the sparse one NumericalError when
// a factorization fails (out of memory).
WellPosedness condition12(const SparseMatrix& B, const SparseMatrix& G,
                          Condition12Method method = Condition12Method::automatic,
                          int dense_limit = kWellposednessDenseLimit);

// The dense reference method alone.
WellPosedness condition12_dense(const SparseMatrix& B, const SparseMatrix& G,
                                int dense_limit = kWellposednessDenseLimit);

// G for constraints at vertices (one row each, fixed vertices skipped: a Dirichlet
// vertex is not an unknown): scalar W^h: row −e_v (the obstacle u(a_v) ≥ g, seed eq. 16);
// vector W^h: row n_x e_{v,x} + n_y e_{v,y} (+ n_z e_{v,z} in 3D: the normal
// displacement u·n ≤ gap), which needs `normal` (one for all) or `normals` (one per
// vertex, e.g. a curved obstacle's).
// Columns are the free dofs of `bc`.
SparseMatrix vertex_constraint_matrix(const FESpace& W, const DirichletLift& bc, const std::vector<int>& vertices,
                                      std::optional<Point> normal = std::nullopt,
                                      const std::vector<Point>& normals = {});

// What condition (12) needs besides the mesh and the pair.
struct WellPosednessSetup {
  std::vector<int> dirichlet_parts;       // indices into mesh.part_names
  std::vector<int> constrained_vertices;  // where the constraint acts (fixed ones skipped)
  int components = 1;                     // 2: plane elasticity
  std::optional<Point> normal;            // components = 2: the constraint direction
  std::vector<Point> normals;             // ... or one per constrained vertex
  Condition12Method method = Condition12Method::automatic;
  int dense_limit = kWellposednessDenseLimit;  // for method = dense
};

// Condition (12) for the discretization `spec` on `mesh`: W^h = spec.W, B of the pair
// (or, for a classical model, B = M: the redistributed model takes the constrained
// vertices, all components, as its contact dofs) and G of the constrained vertices.
// Throws InputError when the model cannot be built for this setup (e.g. redistributed
// with every free vertex constrained) or the dense method is asked beyond its limit,
// NumericalError when the sparse method's factorization fails.
WellPosedness condition12_on(const Mesh& mesh, const MassSpec& spec, const WellPosednessSetup& setup);

}  // namespace cdyn
