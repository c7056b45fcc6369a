// ex6_by_hand.cpp — Example 6: the seed's membrane with every matrix in sight, stepped by
// hand.
//
// What it teaches
//   Examples 2–5 call build_scalar_wave and make_time_scheme, which keep the linear
//   algebra of the seed's method inside the kernel.  Here it is written out: the program
//   assembles A, B, C and L of the pair W^h = P1+, H^h = P0 (seed eq. 10), forms
//   M = BᵀC⁻¹B (eq. 11) and sees that it is singular, writes the constraint set K̄^h as
//   bounds, and takes the midpoint steps of docs/schemes.md itself; the only kernel call
//   above the assembly is the QP solver.  The experiment is the seed's
//   ("Numerical experiments"), as in example 2:
//       ü − Δu = f = −0.6 on Ω = ]0,1[²,  u = 0.02 on ∂Ω and at t = 0,  u̇(0) = 0,
//       u(a_i) ≥ 0 at every vertex a_i,  h = 0.1 (n = 10),  dt = 0.001,  T = 0.8,
//   and the energy J of Theorem 2 is printed as it goes.
//
// How to run
//   build-X/examples/ex6_by_hand                    (800 steps, well under a second)
//   The kernel's own pipeline runs the same problem: cdyn run --set mesh.n=10;
//   ctest -R example_6 compares the two energy traces.
//
// Files: kernel/cdyn/fe/fe_space.hpp, fe/dirichlet.hpp, fe/assembly.hpp, qp/bound_qp.hpp,
// qp/step_solver.hpp; docs/equations.md §4–§7, docs/schemes.md ("Midpoint, constraint on
// the half step").
#include <Eigen/Dense>
#include <cdyn/fe/assembly.hpp>
#include <cdyn/fe/dirichlet.hpp>
#include <cdyn/fe/fe_space.hpp>
#include <cdyn/mesh/mesh.hpp>
#include <cdyn/qp/step_solver.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

using namespace cdyn;
using Vector = Eigen::VectorXd;

int main() {
  // ----- 1. The mesh (seed, "Numerical experiments") ----------------------------------------
  // n × n squares of the unit square, each cut along its diagonal; boundary parts 0..3
  // are bottom, right, top, left.
  const int n = 10, steps = 800;
  const double dt = 0.001, c = 1.0 / dt;  // T = steps · dt = 0.8
  const Mesh mesh = unit_square_mesh(n);

  // ----- 2. The spaces W^h, H^h (eq. 9) and the Dirichlet lift (eq. 4) ------------------------
  // W^h = P1+: the hat function φ_i of each vertex plus one bubble 27λ0λ1λ2 per triangle
  // (scalar dof n_vertices + T).  The bubble vanishes at the vertices, so a vertex
  // coefficient is the vertex value.  H^h = P0: one constant per triangle (dof T).
  const FESpace W(mesh, Element::P1Bubble);
  const FESpace H(mesh, Element::P0);
  // u = 0.02 on ∂Ω: the full coefficient vector is P U + U_D, U the free coefficients
  // (the unknowns), P their injection, U_D the data on the fixed dofs and 0 elsewhere.
  const DirichletLift bc(W, {0, 1, 2, 3});
  const Field u0 = [](double, double, double) { return 0.02; };  // also u(0)
  const Vector UD = bc.lifting(W, {u0});
  const int N_W = bc.n_free(), N_H = H.n_dofs();

  // ----- 3. A, B, C, L (eq. 10) on the free dofs --------------------------------------------
  // A_ij = ∫∇φ_i·∇φ_j, L_i = ∫f φ_i, B_ij = ∫ψ_i φ_j (rows H^h, columns W^h), C_ij = ∫ψ_i ψ_j.
  // With U_D moved to the right-hand side, A U = L on W^h becomes A_ff U = (L − A U_D)_f.
  // A_full and L_full are kept: the energy J is that of the full field.
  const SparseMatrix A_full = assemble_laplace(W);
  const Vector L_full = assemble_load(W, Field([](double, double, double) { return -0.6; }));
  const SparseMatrix A = bc.restrict(A_full);
  const Vector L = bc.restrict(Vector(L_full - A_full * UD));
  // P0 velocities know no Dirichlet condition: only B loses its fixed columns.
  const SparseMatrix B = bc.restrict_columns(assemble_mass(H, W));
  const SparseMatrix C = assemble_mass(H, H);

  // ----- 4. M = Bᵀ C⁻¹ B (eq. 11): the inertia, and its kernel F = Ker B -------------------------
  // C is diagonal for P0 (C_TT = |T|), so C⁻¹B is B with row T divided by |T| and M is
  // sparse.  xᵀMx = |C^{-½}Bx|² ≥ 0, and Ker M = Ker B: a displacement rate that leaves
  // every cell mean unchanged carries no kinetic energy.
  const SparseMatrix CinvB = C.diagonal().cwiseInverse().asDiagonal() * B;
  const SparseMatrix M = SparseMatrix(B.transpose()) * CinvB;
  const Eigen::Index rank_B = Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd(B)).rank();
  std::printf("N_W = %d free dofs of W^h (%d vertices + %d bubbles), N_H = %d cells\n", N_W,
              N_W - mesh.n_cells(), mesh.n_cells(), N_H);
  std::printf("rank B = %d, dim Ker B = N_W - rank B = %d >= N_W - N_H = %d: M is singular\n",
              static_cast<int>(rank_B), N_W - static_cast<int>(rank_B), N_W - N_H);
  // An element of Ker B, by hand: lift the centre vertex v by 1 and lower the bubble of
  // each triangle T around it by B_Tv / B_Tb(T), so that no cell mean moves.  This is
  // why rank B = N_H: the bubble columns alone span R^{N_H} (bubble b(T) sits in row T
  // only), and each free vertex adds one direction to Ker B, where the constraints act
  // (condition (12), example 1).
  const int v = bc.free_index(W.vertex_dof((n / 2) * (n + 1) + n / 2));
  Vector z = Vector::Zero(N_W);
  z[v] = 1.0;
  int around = 0;
  for (SparseMatrix::InnerIterator it(B, v); it; ++it, ++around) {
    const int T = static_cast<int>(it.row()), b = bc.free_index(mesh.n_vertices() + T);
    z[b] = -it.value() / B.coeff(T, b);
  }
  std::printf("centre vertex up, its %d bubbles down: |Bz| = %.1e, |Mz| = %.1e, z'Az = %.3f > 0\n", around,
              (B * z).norm(), (M * z).norm(), z.dot(A * z));

  // ----- 5. The bounds K̄^h (eq. 10, 16): u(a) ≥ g(a) at the free vertices --------------------
  // The constraint acts on vertex values only, so G = −I on the vertex dofs and α = −g:
  // a lower bound per free vertex, none on the bubbles.  The value at vertex a is
  // (P U + U_D)_a, so the bound on U is g − U_D there (U_D is 0 at a free dof; a fixed
  // vertex carries u = 0.02 ≥ 0 and no constraint).
  const double inf = std::numeric_limits<double>::infinity();
  Vector lower = Vector::Constant(N_W, -inf);
  for (int a = 0; a < mesh.n_vertices(); ++a) {
    const int i = bc.free_index(W.vertex_dof(a));
    if (i >= 0) lower[i] = 0.0 /* g(a) */ - UD[W.vertex_dof(a)];
  }

  // ----- 6. The midpoint step on eq. (10), constraint on the half step (docs/schemes.md) --------
  //   Bᵀ(V^{n+1} − Vⁿ)c + A U^{n+½} = L + Gᵀλ,   C(Vⁿ + V^{n+1})/2 = B(U^{n+1} − Uⁿ)c.
  // Apply BᵀC⁻¹ to the second equation: Bᵀ(Vⁿ + V^{n+1}) = 4M(U^{n+½} − Uⁿ)c, eliminate
  // BᵀV^{n+1} from the first, and U^{n+½} is the minimizer over K̄^h of ½XᵀSX − rᵀX with
  //   S = 4Mc² + A,   r = 4MUⁿc² + 2BᵀVⁿc + L        (KKT: SX − r = Gᵀλ, λ ≤ 0).
  // S is SPD although M is not: A_ff is SPD (u is fixed on ∂Ω), docs/equations.md §6.
  // The tolerance on the KKT residual is the one of the seed's scene in `cdyn run`:
  // U^{n+1} = 2U^{n+½} − Uⁿ carries a step's error forward undamped.
  QPOptions options;
  options.tol = 1e-12;
  auto solver = make_step_solver("pdas", options);
  BoundQP qp;
  qp.S = 4 * c * c * M + A;
  qp.lower = lower;
  qp.upper = Vector::Constant(N_W, inf);

  // The initial state: U⁰ interpolates u(0) = 0.02 (its bubble coefficients are 0, u(0)
  // is affine); V⁰ solves C V⁰ = B U̇⁰ (eq. 11) with U̇⁰ = 0.
  Vector U = bc.restrict(W.interpolate(u0));
  Vector V = Vector::Zero(N_H);

  // ----- 7. The energy J of Theorem 2 ----------------------------------------------------------
  //   J = ½VᵀCV + ½uᵀA u − Lᵀu,  u = P U + U_D the full field (A_full, L_full).
  // ½VᵀCV = ½U̇ᵀMU̇ is the kinetic energy the velocity space sees.  Without an active
  // constraint the step keeps J to round-off; with one, J^{n+1} − Jⁿ = (U^{n+1} − Uⁿ)ᵀGᵀλ,
  // the work of the contact force over the step, small because the constraints act on
  // massless directions (Ker B).
  auto kinetic = [&](const Vector& V) { return 0.5 * V.dot(C * V); };
  auto potential = [&](const Vector& U) {
    const Vector u = bc.extend(U, UD);
    return 0.5 * u.dot(A_full * u) - L_full.dot(u);
  };
  const double J0 = kinetic(V) + potential(U);

  std::printf("%5s %6s %22s %22s %22s %6s\n", "step", "t", "1/2 V'CV", "1/2 u'Au - L'u", "J", "active");
  QPResult X;  // the last step's QP solution: X.X = U^{n+½}, the warm start of the next
  double drift = 0.0, violation = 0.0;
  for (int k = 0; k <= steps; ++k) {
    if (k > 0) {
      qp.r = 4 * c * c * (M * U) + 2 * c * (B.transpose() * V) + L;
      X = solver->solve(qp, k > 1 ? &X : nullptr);
      // U^{n+1} = 2U^{n+½} − Uⁿ, as the seed's experiments take it.  Its massless part
      // (Ker B) is an extrapolation that may dip below the obstacle (the violation printed
      // at the end); cdyn's midpoint replaces it by the static solution of eq. (14), which
      // changes no massful quantity (schemes/full_step.hpp; compared with
      // `cdyn run --set time.reconstruct=false`).
      const Vector U1 = 2.0 * X.X - U;
      V = 2.0 * c * (CinvB * (U1 - U)) - V;       // C(Vⁿ + V^{n+1})/2 = B(U^{n+1} − Uⁿ)c
      U = U1;
      violation = std::max(violation, (lower - U).maxCoeff());  // only U^{n+½} is constrained
    }
    const double Ek = kinetic(V), Ep = potential(U), J = Ek + Ep;
    drift = std::max(drift, std::abs(J - J0) / std::abs(J0));
    if (k % 100 == 0)
      std::printf("%5d %6.3f %22.15e %22.15e %22.15e %6d\n", k, k * dt, Ek, Ep, J, static_cast<int>(X.active.size()));
  }
  std::printf("max over t of |J - J0|/|J0| = %.3e, max violation of u(a) >= 0 at the steps' ends = %.3e\n",
              drift, violation);
  // ----- 8. Reading it ------------------------------------------------------------------------
  // The membrane falls freely (J constant to 1e-12), touches the obstacle at t = 0.248
  // and bounces: J moves by at most 1.2 % over the impacts, where a pair with inertia at
  // the constrained vertices gains O(1) (P1/P1: |J − J0| = 2.25 J0, docs/experiments.md).  The trace is that of
  // `cdyn run --set mesh.n=10` to the QP tolerance, not to the bit: cdyn solves the same
  // QPs with the bubbles condensed out (qp/condensation.hpp) and forms r as
  // Bᵀ(4c²C⁻¹BUⁿ + 2cVⁿ).  Measured: |J − J_cdyn| ≤ 8.5e-11 J0 over the 800 steps
  // (examples/check_examples.py, example6).
  return 0;
}

/* The output (Release build):

N_W = 281 free dofs of W^h (81 vertices + 200 bubbles), N_H = 200 cells
rank B = 200, dim Ker B = N_W - rank B = 81 >= N_W - N_H = 81: M is singular
centre vertex up, its 6 bubbles down: |Bz| = 0.0e+00, |Mz| = 3.4e-19, z'Az = 30.667 > 0
 step      t               1/2 V'CV         1/2 u'Au - L'u                      J active
    0  0.000  0.000000000000000e+00  1.199999999999998e-02  1.199999999999998e-02      0
  100  0.100  1.336980031528667e-03  1.066301996846793e-02  1.199999999999660e-02      0
  200  0.200  3.804232188642554e-03  8.195767811343005e-03  1.199999999998556e-02      0
  300  0.300  4.212495794792969e-03  7.799407252600817e-03  1.201190304739379e-02     13
  400  0.400  2.250468930636452e-03  9.758033569361172e-03  1.200850249999762e-02      0
  500  0.500  1.621714229651338e-03  1.038678827034943e-02  1.200850250000077e-02      0
  600  0.600  2.256005504951682e-03  9.752496995053660e-03  1.200850250000534e-02      0
  700  0.700  2.404909618674311e-03  9.604631707472753e-03  1.200954132614706e-02      0
  800  0.800  2.345393973504439e-03  9.607618073172102e-03  1.195301204667654e-02     26
max over t of |J - J0|/|J0| = 1.185e-02, max violation of u(a) >= 0 at the steps' ends = 2.682e-04
*/
