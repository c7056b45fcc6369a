// schemes/time_scheme.hpp — time integration of the semi-discrete constrained problem.
//
// Every implicit scheme (docs/schemes.md; a time-discrete seed eq. 16) advances (U, V) by one QP
//     min ½ XᵀSX − rᵀX  over  lower ≤ X ≤ upper,
// followed by an explicit update.  S is fixed for a run (dt is), so the QP object and
// the step solver's factorizations are reused from step to step; the previous step's
// result warm-starts the next.  Derivations: docs/schemes.md.
#pragma once

#include <optional>

#include <Eigen/Core>
#include <memory>
#include <string>

#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/qp/step_solver.hpp"
#include "cdyn/schemes/damping.hpp"
#include "cdyn/schemes/scheme_memory.hpp"

namespace cdyn {

// The discrete state: time, displacement (free dofs of W^h), velocity (H^h).
struct State {
  double t = 0.0;
  Eigen::VectorXd U, V;
  Eigen::VectorXd reaction;  // Gᵀλ of the last step on the free dofs (λ the seed's multiplier)
  // With friction (ConstrainedProblem::friction), of the last step: the status of each
  // friction node (qp/friction_qp.hpp: 0 open, 1 stick, 2 slip), and the slip on the
  // free unknowns, U^{n+1}_T − Uⁿ_T on the friction nodes' tangential unknowns and 0
  // elsewhere (in the nodal frames, as `reaction`: p.global() gives it in x, y, z).  The
  // tangential force is `reaction` on the same unknowns (problems/friction.hpp,
  // tangential_magnitude).  Empty without friction or before a step.
  std::vector<int> contact_status;
  Eigen::VectorXd slip;
};

// What one step cost and found.
struct StepStats {
  int qp_iterations = 0;
  double qp_seconds = 0.0;
  int active = 0;             // constraints active at the step's QP solution
  double kkt_residual = 0.0;
  // False when the step QP stopped above its tolerance.  That only returns when the
  // solver was built with QPOptions::throw_on_failure = false (a caller that wants to
  // look at the failing step: benchmarks, solver studies); by default the failure
  // throws NumericalError and a scheme never hands back an unconverged step.  A
  // caller that opts out must check this flag (docs/stability.md, "Solver stress").
  bool converged = true;
  // The full-step reconstruction of eq. (14) (schemes/full_step.hpp), when the scheme
  // makes one: its QP's KKT residual, and the energy corrections of discrete_gradient.
  double reconstruction_kkt = 0.0;
  // Its cost: the seconds of the step's reconstructions (right-hand side, QP, W), which
  // step_s includes and qp_seconds does not, and the iterations of their QP solves.
  double reconstruction_seconds = 0.0;
  int reconstruction_iterations = 0;
  int energy_iterations = 0;  // discrete_gradient: step QPs solved (1 without a switch)
  int substeps = 0;           // discrete_gradient: halvings of dt at a stiff switch
  // The step's work of the data in t on the body (a load L(t), a moving obstacle;
  // problems/data_work.hpp), set by a scheme whose energy balances it exactly: with
  // discrete_gradient H^{n+1} + W_d − Hⁿ = external_work (0 when nothing depends on t).
  std::optional<double> external_work;
  // The work of the Rayleigh damping force over the step (schemes/damping.hpp), ≥ 0:
  // J^{n+1} + dissipated − Jⁿ is the contact's work (and the data's) for the midpoint
  // rules, 0 for discrete_gradient, ≤ 0 for backward Euler (docs/schemes.md).
  double dissipated = 0.0;
  // The work of the friction forces over the step's slip, W_f = Σ s_a |U^{n+1}_T − Uⁿ_T|
  // ≥ 0 (qp/friction_qp.hpp; 0 without friction): the midpoint rule's balance becomes
  // J^{n+1} + W_d + W_f − Jⁿ = (U^{n+1} − Uⁿ)_Nᵀ λ_N, the normal contact's work.
  double friction_work = 0.0;
  // (On a share of the step QP, StepSolver::solves_a_share: dissipated and friction_work
  // are this rank's part, which the program sums over the ranks; external_work is the
  // whole problem's.)
};

// How a scheme's full-step states U^{n+1} get their massless part Ker B (eq. 14):
//  - solved: the step's QP has U^{n+1} as unknown and minimizes the potential at t^{n+1}
//    on Ker B (backward_euler, newmark), or Ker B = {0} (energy_conserving and
//    paoli_schatzman, which need an invertible M);
//  - reconstructed: eq. (14) solved after the step (schemes/full_step.hpp);
//  - extrapolated: U^{n+1} = 2U^{n+½} − Uⁿ as it comes (time.reconstruct = false, or a
//    constrained unknown that Ker B cannot move).
enum class FullSteps { Solved, Reconstructed, Extrapolated };
std::string to_string(FullSteps f);

// The discrete energy J = ½VᵀCV + ½UᵀAU − LᵀU (seed, Theorem 2), split in its parts.
struct Energy {
  double kinetic = 0.0, potential = 0.0;
  double total() const { return kinetic + potential; }
};

class TimeScheme {
 public:
  virtual ~TimeScheme() = default;
  virtual std::string name() const = 0;
  // Advances s from t to t + dt.
  virtual StepStats step(State& s) = 0;
  // The energy of the state in the form the scheme's identity is written for
  // (docs/schemes.md): J(Uⁿ, Vⁿ) for the one-step schemes; the three-level schemes
  // evaluate the potential part between the last two displacements.
  virtual Energy energy(const State& s) const = 0;
  // Makes the initial state one the scheme's energy identity starts from: a scheme that
  // reconstructs its full steps (eq. 14) replaces the massless part of U⁰ by its
  // static solution — same B U⁰, the same dynamics.  Call once before the first step
  // (the first step calls it otherwise).
  virtual void initialize(State& s) { (void)s; }
  // How the full-step states get their massless part.
  virtual FullSteps full_steps() const { return FullSteps::Solved; }
  // What the scheme remembers of the steps before (schemes/scheme_memory.hpp): with the
  // State, everything needed to go on.
  virtual SchemeMemory memory() const = 0;
  // Goes on from a memory (this scheme's, or that of a scheme made alike in another
  // run), clearing the step solver's caches: after restore(m) this scheme computes, from
  // the State that went with m, the same steps bit for bit as any scheme made alike and
  // restored from m.  InputError (parameter "memory") for a memory of another scheme.
  virtual void restore(const SchemeMemory& m) = 0;
};

// The parameters of the schemes that have some (docs/schemes.md).
struct SchemeParameters {
  double beta = 0.25, gamma = 0.5;  // newmark (the trapezoidal rule by default)
  double restitution = 0.0;         // paoli_schatzman's e ∈ [0, 1]
  bool condense = true;             // the implicit schemes: eliminate the bubbles (schemes/step_qp_scheme.hpp)
  // midpoint, midpoint_end, discrete_gradient: solve eq. (14) for the massless part of
  // every full-step state (schemes/full_step.hpp), to `tol` (kkt_residual).
  bool reconstruct = true;
  double tol = 1e-10;
  // ... by pdas's CG alone, without a factor (set with the step's solver.linear = "cg")
  bool reconstruct_by_cg = false;
  // discrete_gradient: the largest energy error of a step, relative to the size of the
  // terms of ΔH = ΔK + ΔΨ (½VᵀCV, |Ψ| and the kinetic change's two parts: the round-off
  // of ΔH is a few ε of them; docs/schemes.md, "The discrete gradient scheme").
  double energy_tol = 1e-12;
  // The frictional step (qp/friction_solvers.hpp) is solved to friction_residual ≤ tol
  // (the scheme's tol above, the step QP's own).
  // Rayleigh damping D = αM + βA (backward_euler, midpoint, midpoint_end,
  // discrete_gradient; the other schemes refuse it).
  RayleighDamping damping;
};

// name: backward_euler | midpoint | midpoint_end | newmark | paoli_schatzman |
// energy_conserving | discrete_gradient.  The problem and the solver must outlive the scheme.  Throws
// InputError for an unknown name, dt <= 0, parameters out of range, a mass model the
// scheme does not accept (paoli_schatzman needs an invertible M in W^h), or damping
// asked of a scheme without it (parameter "damping").
std::unique_ptr<TimeScheme> make_time_scheme(const std::string& name, const ConstrainedProblem& problem,
                                             StepSolver& solver, double dt, const SchemeParameters& parameters = {});
std::vector<std::string> time_scheme_names();

// The scheme cdyn recommends for a problem (docs/schemes.md, "which scheme is the
// default"): discrete_gradient where the full steps of eq. (14) exist and move every
// constrained unknown (P1+/P0, P1+/P1, P2/P1, the redistributed mass), midpoint_end
// otherwise — the two
// never gain energy beyond round-off.
std::string recommended_scheme(const ConstrainedProblem& problem);

// The initial velocity V⁰ in H^h from a displacement rate U̇⁰ on the free dofs:
// C V⁰ = B U̇⁰ (seed eq. 11's initial condition).
Eigen::VectorXd initial_velocity(const ConstrainedProblem& problem, const Eigen::VectorXd& Udot0);

}  // namespace cdyn
