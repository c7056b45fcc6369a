// ex1_condition12.cpp — Example 1: the spaces of a pair W^h/H^h and condition (12).
//
// What it teaches
//   The seed's semi-discretization carries the displacement in W^h and the velocity in
//   H^h.  The matrix B_ij = ∫ψ_i φ_j couples them, and the displacements it does not
//   see, F = Ker B, carry no inertia.  Condition (12) asks the constraints G U ≤ α to
//   act independently on F:
//       β = inf_Q sup_{W∈F} QᵀGW / (|Q||W|) = σ_min(G Z) > 0,   Z an orthonormal basis of Ker B.
//   Then the semi-discrete problem is a Lipschitz ODE (Theorem 1) that conserves energy
//   (Theorem 2).  We build the spaces of each pair of the seed on the membrane of its
//   experiments (unit square, u fixed on ∂Ω, u(a_i) ≥ 0 at every vertex), assemble B
//   and G, and compute β: P1+/P0 satisfies (12), P1/P1 and P1/P0 do not.
//
// How to run
//   build-X/examples/ex1_condition12            (about a second)
//   CTest: ctest -R example_1 (compares every β with `cdyn wellposed --json`).
//
// Files to read next to it: kernel/cdyn/fe_space.hpp, fe/element.hpp, fe/dirichlet.hpp,
// mass/mass_model.hpp (mixed_blocks), wellposedness/condition12.hpp, docs/semi_discretization.md.
#include <cdyn/fe/dirichlet.hpp>
#include <cdyn/fe/fe_space.hpp>
#include <cdyn/mass/mass_model.hpp>
#include <cdyn/mesh/mesh.hpp>
#include <cdyn/wellposedness/condition12.hpp>
#include <cstdio>
#include <string>
#include <vector>

using namespace cdyn;

int main() {
  for (int n : {4, 6, 10}) {
    // ----- 1. The mesh ------------------------------------------------------------------
    // FreeFEM's square(n,n): n × n cells, each cut along its lower-left to upper-right
    // diagonal.  Boundary parts 0..3 are "bottom", "right", "top", "left".
    const Mesh mesh = unit_square_mesh(n);
    const std::vector<int> boundary = {0, 1, 2, 3};
    std::vector<int> vertices(mesh.n_vertices());
    for (int v = 0; v < mesh.n_vertices(); ++v) vertices[v] = v;  // u(a_v) ≥ g everywhere
    std::printf("unit square n = %d: %d vertices, %d triangles, h = %.4f\n", n, mesh.n_vertices(), mesh.n_cells(),
                mesh.h_max());
    std::printf("  %-7s %6s %6s %8s %5s %17s  %s\n", "pair", "N_W", "N_H", "dimKerB", "N_g", "beta", "(12)");

    // The pairs of the seed's experiments, in its order.
    for (const std::string pair : {"P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1"}) {
      const std::string w_name = pair.substr(0, pair.find('/')), h_name = pair.substr(pair.find('/') + 1);

      // ----- 2. The displacement space W^h and its Dirichlet condition -------------------
      // A space is a reference element repeated over the cells (fe/fe_space.hpp).  P1+ adds
      // one cubic bubble 27λ0λ1λ2 per triangle to P1; its vertex dofs stay the vertex
      // values, which is where the constraints act.  The DirichletLift splits the dofs
      // of W^h into free and fixed (u = 0.02 on ∂Ω): only free dofs are unknowns.
      const FESpace W(mesh, element_from_string(w_name));
      const DirichletLift bc(W, boundary);

      // ----- 3. B = ∫ψ_i φ_j on the free dofs (seed eq. 10) -------------------------------
      // mixed_blocks assembles B (N_H × N_W) and C (N_H × N_H) of the pair, with the
      // velocity dofs of a continuous H^h removed where the displacement is prescribed.
      // ρ = 1: condition (12) does not depend on the density.
      const MixedBlocks blocks = mixed_blocks(W, bc, element_from_string(h_name), 1.0);

      // ----- 4. G: one row per constrained vertex (seed eq. 16) ---------------------------
      // u(a_v) ≥ g reads −U_v ≤ −g: the row −e_v.  Boundary vertices are fixed, not
      // unknowns, and get no row.
      const SparseMatrix G = vertex_constraint_matrix(W, bc, vertices);

      // ----- 5. Condition (12): β = σ_min(G Z) --------------------------------------------
      // dim Ker B < N_g forces β = 0: P1/P1 (B = C_ff is invertible) and P1/P0 (more
      // cells than free vertices, B of full column rank) have no inertia-free
      // displacement at all.  P1+/P0 has one bubble per cell, so B (cells × (vertices +
      // cells)) is onto and Ker B has one direction per free vertex: N_g = dim Ker B,
      // and the constraints act on it independently.
      WellPosedness w = condition12(blocks.B, G);
      w.pair = pair;
      std::printf("  %-7s %6d %6d %8d %5d %17.10e  %s\n", pair.c_str(), w.n_W, w.n_H, w.dim_ker_B, w.n_g, w.beta,
                  w.satisfied ? "yes" : "no");
    }
  }
  // ----- 6. What the numbers say ----------------------------------------------------------
  // P1+/P0 keeps β near 0.3 as h → 0 (a closed form, tests/unit/test_wellposedness.cpp:
  // β = 1/√(1 + (20/27)² λ_max(EᵀE)) → 27/√7929 ≈ 0.3032, E the cell–vertex incidence),
  // so the constraint forces stay bounded; the seed's P1/P1 and P1/P0 fail on every mesh.
  return 0;
}

/* The output (Release build):

unit square n = 4: 25 vertices, 32 triangles, h = 0.3536
  pair       N_W    N_H  dimKerB   N_g              beta  (12)
  P1/P1        9      9        0     9  0.0000000000e+00  no
  P1/P0        9     32        0     9  0.0000000000e+00  no
  P1+/P0      41     32        9     9  3.4166034875e-01  yes
  P1+/P1      41      9       32     9  3.0321770424e-01  yes
  P2/P1       49      9       40     9  8.4004367595e-01  yes
unit square n = 6: 49 vertices, 72 triangles, h = 0.2357
  pair       N_W    N_H  dimKerB   N_g              beta  (12)
  P1/P1       25     25        0    25  0.0000000000e+00  no
  P1/P0       25     72        0    25  0.0000000000e+00  no
  P1+/P0      97     72       25    25  3.1963175948e-01  yes
  P1+/P1      97     25       72    25  2.4575277955e-01  yes
  P2/P1      121     25       96    25  7.5865665436e-01  yes
unit square n = 10: 121 vertices, 200 triangles, h = 0.1414
  pair       N_W    N_H  dimKerB   N_g              beta  (12)
  P1/P1       81     81        0    81  0.0000000000e+00  no
  P1/P0       81    200        0    81  0.0000000000e+00  no
  P1+/P0     281    200       81    81  3.0900178713e-01  yes
  P1+/P1     281     81      200    81  1.6839568879e-01  yes
  P2/P1      361     81      280    81  6.8047803862e-01  yes
*/
