// ex2_membrane.cpp — Example 2: the membrane over an obstacle by the seed's method,
// step by step.
//
// What it teaches
//   The seed's experiment (Renard, "Numerical experiments"): on Ω = ]0,1[²
//       ü − Δu = f = −0.6,   u = 0.02 on ∂Ω and at t = 0,   u̇(0) = 0,
//       u(a_i) ≥ 0 at every vertex a_i,
//   with W^h = P1+ (P1 plus a cubic bubble per triangle) and H^h = P0.  Condition (12)
//   holds (example 1), so the semi-discrete problem
//       M Ü + A U = L + Gᵀλ,  G U ≤ α,  λ ≤ 0,  λᵀ(G U − α) = 0      (seed eq. 16)
//   is well posed and conserves J = ½VᵀCV + ½UᵀAU − LᵀU (Theorem 2).  The midpoint
//   scheme with the constraint on the half step keeps J nearly constant through the
//   impacts; each step is one bound-constrained QP.  This program goes through the
//   data flow of the kernel one stage at a time and prints the energy as it goes.
//
// How to run
//   build-X/examples/ex2_membrane                  (800 steps, under a second)
//   The same run by the command line:
//   cdyn run --set mesh.n=10      (the default scene: dt = 0.001, T = 0.8)
//   prints the same energies into history.csv; ctest -R example_2 compares them.
//
// Files: kernel/cdyn/scalar_wave.hpp, problems/constrained_problem.hpp, mass/mass_model.hpp,
// schemes/time_scheme.hpp, qp/bound_qp.hpp; docs/semi_discretization.md, docs/schemes.md.
#include <cdyn/qp/step_solver.hpp>
#include <cdyn/problems/scalar_wave.hpp>
#include <cdyn/schemes/time_scheme.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace cdyn;

int main() {
  // ----- 1. Mesh ------------------------------------------------------------------------
  // h = 0.1 as in the seed's figures, but on n = 10 cells per side.
  const int n = 10;
  const double dt = 0.001, T = 0.8;  // the seed's dt; docs/experiments.md, first table
  const Mesh mesh = unit_square_mesh(n);

  // ----- 2. The problem: spaces, matrices, mass model, constraints ----------------------
  // build_scalar_wave does, in order: W^h = P1+ and its Dirichlet lifting (fe/dirichlet.hpp);
  // A = ∫∇φ_i·∇φ_j and L = ∫f φ_i (fe/assembly.hpp); M = Bᵀ C⁻¹ B from the pair P1+/P0
  // (mass/mass_model.hpp; C is diagonal for P0, so M is sparse); the bounds U_v ≥ g at the
  // free vertices, i.e. K̄^h = {G U ≤ α} with G = −I there.  Everything lives on the
  // free dofs; the full field is P U + U_D.
  ScalarWaveData data;
  data.mass = MassSpec::pair(Element::P1Bubble, Element::P0);  // W^h = P1+, H^h = P0
  data.f = [](double, double, double) { return -0.6; };
  data.dirichlet_parts = {0, 1, 2, 3};    // the whole boundary
  data.dirichlet_value = [](double, double, double) { return 0.02; };
  data.obstacle_g = [](double, double, double) { return 0.0; };  // u(a_i) ≥ 0
  const ConstrainedProblem problem = build_scalar_wave(mesh, data);
  std::printf("P1+/P0 on the unit square, n = %d: %d free dofs, %d velocity dofs, %d constraints\n", n,
              problem.n_free(), problem.mass->n_velocity(), static_cast<int>(problem.constrained.size()));

  // ----- 3. The step solver and the scheme -----------------------------------------------
  // Midpoint with the constraint on the half step (docs/schemes.md): the unknown is
  // X = U^{n+½}, and with c = 1/dt each step solves
  //     min ½ Xᵀ(4Mc² + A)X − rᵀX,  r = 4MUⁿc² + 2BᵀVⁿc + L,  X_v ≥ g_v,
  // then U^{n+1} = 2X − Uⁿ and C(Vⁿ + V^{n+1})/2 = B(U^{n+1} − Uⁿ)c.  The QP goes to the
  // primal-dual active set solver, which reuses its Cholesky factor from step to step.
  QPOptions options;
  options.tol = 1e-12;  // an inexact contact dof would be carried forward by U^{n+1} = 2X − Uⁿ
  auto solver = make_step_solver("pdas", options);
  // After each step the massless part of U^{n+1} (Ker B: here the bubbles' share of the
  // vertex values) is made the static solution of eq. (14) for the step's B U^{n+1}
  // (schemes/full_step.hpp), solved as tightly as the step: a physical state, on or above
  // the obstacle, whose J the seed's Theorem 2 is about.
  SchemeParameters parameters;
  parameters.tol = options.tol;
  auto scheme = make_time_scheme("midpoint", problem, *solver, dt, parameters);

  // ----- 4. The initial state ------------------------------------------------------------
  // U⁰ interpolates u₀ = 0.02 on the free dofs (its bubbles are 0: u₀ is affine);
  // V⁰ ∈ H^h solves C V⁰ = B U̇⁰ (seed eq. 11), here U̇⁰ = 0.
  State s;
  s.U = problem.unknowns(problem.W->interpolate([](double, double, double) { return 0.02; }));
  s.V = initial_velocity(problem, Eigen::VectorXd::Zero(problem.n_free()));
  scheme->initialize(s);  // U⁰'s massless part from eq. (14), as every full step's
  const double J0 = scheme->energy(s).total();

  // ----- 5. The time loop ----------------------------------------------------------------
  // J splits into ½VᵀCV (kinetic) and ½UᵀAU − LᵀU (potential, of the full field).  The
  // membrane falls, touches the obstacle (active > 0: constraints active at that
  // step), and J stays near J0: the constraints act on F = Ker B, displacements that
  // carry no inertia, so an impact is not a jump of velocity at a massive node.
  std::printf("%5s %6s %22s %22s %22s %6s\n", "step", "t", "E_kin", "E_pot", "J", "active");
  const int steps = static_cast<int>(T / dt + 0.5);
  double drift = 0.0;
  for (int k = 0; k <= steps; ++k) {
    StepStats stats;
    if (k > 0) stats = scheme->step(s);
    const Energy E = scheme->energy(s);
    drift = std::max(drift, std::abs(E.total() - J0) / std::abs(J0));
    if (k % 40 == 0)
      std::printf("%5d %6.3f %22.15e %22.15e %22.15e %6d\n", k, s.t, E.kinetic, E.potential, E.total(), stats.active);
  }
  // ----- 6. The energy balance ----------------------------------------------------------
  // The scheme's identity (docs/schemes.md): J^{n+1} − Jⁿ = (U^{n+1} − Uⁿ)ᵀGᵀλ, the work
  // of the contact force over a step; zero without contact, small for a pair satisfying
  // (12), and it goes to 0 with dt (tests/stability/test_energy_convergence.cpp).
  std::printf("|J(T) - J0|/|J0| = %.3e, max over t of |J - J0|/|J0| = %.3e\n",
              std::abs(scheme->energy(s).total() - J0) / std::abs(J0), drift);
  return 0;
}

/* The output (Release build):

P1+/P0 on the unit square, n = 10: 281 free dofs, 200 velocity dofs, 81 constraints
 step      t                  E_kin                  E_pot                      J active
    0  0.000  0.000000000000000e+00  1.199999999999998e-02  1.199999999999998e-02      0
   40  0.040  2.545119893747735e-04  1.174548801062433e-02  1.199999999999910e-02      0
   80  0.080  9.099109102114569e-04  1.109008908978541e-02  1.199999999999687e-02      0
  120  0.120  1.808802863030815e-03  1.019119713696109e-02  1.199999999999190e-02      0
  160  0.160  2.812728500309866e-03  9.187271499675955e-03  1.199999999998582e-02      0
  200  0.200  3.804232188632181e-03  8.195767811347135e-03  1.199999999997932e-02      0
  240  0.240  4.687502837548647e-03  7.312497162427694e-03  1.199999999997634e-02      0
  280  0.280  1.885773285700380e-03  1.001583970297835e-02  1.190161298867873e-02     49
  320  0.320  3.168888372646483e-03  8.839624889126010e-03  1.200851326177249e-02      0
  360  0.360  1.913839377925539e-03  1.009466312203735e-02  1.200850249996288e-02      0
  400  0.400  2.250468930643995e-03  9.758033569322946e-03  1.200850249996694e-02      0
  440  0.440  2.148633603460581e-03  9.859868896507184e-03  1.200850249996776e-02      0
  480  0.480  1.774893008518176e-03  1.023360949145116e-02  1.200850249996934e-02      0
  520  0.520  1.393103008341350e-03  1.061539949163009e-02  1.200850249997144e-02      0
  560  0.560  1.721516189208455e-03  1.028698631076534e-02  1.200850249997379e-02      0
  600  0.600  2.256005504952550e-03  9.752496995020539e-03  1.200850249997309e-02      0
  640  0.640  1.668640034889819e-03  1.032275364570512e-02  1.199139368059494e-02      7
  680  0.680  2.154577899224706e-03  9.854963426884114e-03  1.200954132610882e-02      0
  720  0.720  2.648470545648089e-03  9.359149616231697e-03  1.200762016187979e-02      4
  760  0.760  3.432787019583886e-03  8.576810771959955e-03  1.200959779154384e-02      0
  800  0.800  2.345393973518113e-03  9.607618073861120e-03  1.195301204737923e-02     26
|J(T) - J0|/|J0| = 3.916e-03, max over t of |J - J0|/|J0| = 1.185e-02
*/
