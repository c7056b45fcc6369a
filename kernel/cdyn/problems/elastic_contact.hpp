// problems/elastic_contact.hpp — the elastodynamic Signorini problem of the seed (eqs. 1–6) in
// plane strain (a 2D mesh) or in space (a tetrahedral mesh), as a ConstrainedProblem
// (problems/constrained_problem.hpp):
//
//     ρ ü − div σ(u) = f  in Ω,     σ(u) = λ tr ε(u) I + 2μ ε(u)       (1), (2)
//     σ(u) ν = g_N on Γ_N,   u = u_D on Γ_D,   u(0) = u₀, u̇(0) = u₁     (3)–(5)
//     nodal Signorini contact on Γ_C against rigid obstacles            (6)
//
// Weak form: A_ij = ∫ λ div φ_i div φ_j + 2μ ε(φ_i):ε(φ_j) (assemble_elasticity),
// L_i = ∫_Ω f·φ_i + ∫_{Γ_N} g_N·φ_i (assemble_load, assemble_boundary_load); the inertia
// is the chosen pair's M = ρ Bᵀ C⁻¹ B or a classical mass model (mass/mass_model.hpp).
//
// Rigid obstacles (problems/rigid_obstacle.hpp): planes, or surfaces given by a gap
// function φ(x, t) whose normal comes from its gradient, each with its own contact parts.
// A contact vertex on the parts of several obstacles is constrained by the one it is
// nearest to at t = 0 (one bound per vertex: the node-local rotation turns one normal).
// An obstacle whose φ depends on t moves: the bounds are then K̄^h(t)
// (ConstrainedProblem::moving_bounds), the normals those of t = 0.
//
// Materials.  ρ, λ, μ are one material for the whole body, or one per mesh region
// (Mesh::cell_region, the gmsh physical surfaces): the integrals above are then taken
// cell by cell with the cell's values (fe/cell_coefficient.hpp), which is exact for
// interfaces along cell edges.  A body of one material is computed exactly as before.
//
// The rigid plane (convention, docs/elasticity.md).  The plane passes through the point
// p and n is its unit normal pointing from the obstacle INTO the body's side (the
// obstacle's outward normal).  A contact vertex a may not cross it:
//     (a + u(a) − p)·n ≥ 0   ⇔   n·u(a) ≥ g(a) := −(a − p)·n,
// a LOWER bound on the normal component, the membrane's u ≥ g with e_y replaced by n.
// g(a) ≤ 0 is minus the initial distance to the plane.  With the body's outward normal
// ν = −n on Γ_C this is the seed's u_N = u·ν ≤ −g (eq. 6), and its multiplier λ_N ≤ 0
// is minus the QP reaction on the normal unknown: the contact pressure −λ_N ≥ 0.
//
// The constraint acts on the vertex dofs of each vertex of Γ_C (never on bubbles or
// edge dofs).  For a normal along an axis the bound falls on u_x, u_y or u_z itself;
// otherwise the problem carries the node-local rotation R (problems/nodal_rotation.hpp)
// and its unknowns at the contact nodes are (n·u, t·u), t = (−n_y, n_x), in the plane
// and (n·u, t₁·u, t₂·u) in space.  A vertex whose components are all fixed by Dirichlet
// conditions is not constrained; one with some fixed components (a roller) gets the
// bound m·u_F ≥ g − Σ_fixed n_j u_D,j on its free components F (m the part of n along
// them): on the one free component n has a part along, or on the normal component of
// the free ones, rotated.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "cdyn/fe/cell_coefficient.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/problems/rigid_obstacle.hpp"

namespace cdyn {

// The zero field, the default of every datum below.
inline double zero_field(double, double, double) { return 0.0; }

// An isotropic linear elastic material: density and Lamé parameters.
struct Material {
  double rho = 1.0;
  double lambda = 1.0, mu = 1.0;
};

struct ElasticContactData {
  MassSpec mass;                   // the pair W^h/H^h (P1+/P0 by default) or a classical mass on W^h
  double rho = 1.0;                // density
  double lambda = 1.0, mu = 1.0;   // Lamé parameters (plane strain; lame_parameters(E, ν))
  // Materials by region: (index into mesh.region_names, its material).  The cells of the
  // regions not listed, and every cell of a mesh without regions, take rho, lambda, mu.
  std::vector<std::pair<int, Material>> region_materials;
  // Vectors have one entry per coordinate; the first mesh.dim are used (a 2D body
  // ignores the z entries).
  std::array<Field, 3> f{zero_field, zero_field, zero_field};  // body force (f_x, f_y, f_z)(x, y, z, t)
  std::array<double, 3> gravity{0.0, 0.0, 0.0};     // an acceleration g: ρ g is added to f, ρ of each cell
  bool load_is_constant = true;    // neither f nor the traction depends on t

  std::vector<int> dirichlet_parts;                // Γ_D (indices into mesh.part_names)
  std::vector<int> dirichlet_components;           // the fixed components; empty: all
  std::array<Field, 3> dirichlet_value{zero_field, zero_field, zero_field};  // u_D, constant in time

  std::vector<int> neumann_parts;                  // Γ_N (free parts with a traction)
  std::array<Field, 3> traction{zero_field, zero_field, zero_field};  // g_N = σ ν on Γ_N

  // The obstacles.  Empty: the single plane through obstacle_point with normal
  // obstacle_normal, touched by contact_parts (the shorthand of the first scenes).
  std::vector<RigidObstacle> obstacles;
  std::vector<int> contact_parts;  // Γ_C of the single plane
  Point obstacle_point{0.0, 0.0};  // p, a point of the rigid plane
  Point obstacle_normal{0.0, 1.0}; // n, towards the body (normalized by the builder)
  bool obstacle = true;            // false: the same problem (same M, same unknowns) with no constraint
  bool rotate_always = false;      // rotate even for an axis-aligned n (to test both paths)
};

// Lamé parameters of Young's modulus E and Poisson's ratio ν (plane strain uses the 3D
// ones): λ = Eν / ((1 + ν)(1 − 2ν)),  μ = E / (2(1 + ν)).  InputError unless E > 0 and
// −1 < ν < ½.
struct Lame {
  double lambda = 0.0, mu = 0.0;
};
Lame lame_parameters(double E, double nu);

// ρ, λ, μ on every cell of `mesh`: the material of the cell's region when
// data.region_materials names it, else data's rho, lambda, mu.  Uniform coefficients
// when every cell has the same material (fe/cell_coefficient.hpp).  InputError for a
// region index the mesh does not have, a region listed twice, or a material with
// ρ ≤ 0, μ ≤ 0 or λ + μ ≤ 0 (parameters "rho", "mu", "lambda"; the message names the
// region).  In the plane the ellipticity of plane strain asks λ + μ > 0, in space
// 3λ + 2μ > 0 (a positive bulk modulus).
struct CellMaterials {
  CellCoefficient rho, lambda, mu;
};
CellMaterials cell_materials(const Mesh& mesh, const ElasticContactData& data);

// g(a) = −(a − p)·n: the lower bound of n·u(a) (n normalized) for the single plane.
double obstacle_gap(const ElasticContactData& data, const Point& a);

// The obstacles of the data: `obstacles`, or the single plane when it is empty.
std::vector<RigidObstacle> obstacles_of(const ElasticContactData& data);

// Throws InputError for ρ ≤ 0, μ ≤ 0, λ + μ ≤ 0 (3λ + 2μ ≤ 0 in space), a zero normal,
// a 1D mesh, an obstacle with no contact part, or a gap function without a gradient at
// a contact vertex.
ConstrainedProblem build_elastic_contact(const Mesh& mesh, const ElasticContactData& data);

}  // namespace cdyn
