// discrete_gradient.cpp — an energy-exact full discretization of the singular dynamic
// method: a discrete gradient (Gonzalez 1996) of the reduced potential Ψ.
//
// Under condition (12), with q = C⁻¹B U the velocity-space coordinate of the massful
// part, the semi-discrete problem is the Hamiltonian system (docs/equations.md,
// Theorem 1 and eq. (14))
//     q̇ = V,   C V̇ = −∇Ψ(q),   Ψ(q) = min { ½WᵀAW − LᵀW : C⁻¹B W = q, W ∈ K̄^h },
// H = ½VᵀCV + Ψ(q) the seed's J, and Ψ convex with a Lipschitz gradient.  The scheme
//     q^{n+1} − qⁿ = dt V^{n+½},   C (V^{n+1} − Vⁿ) = −dt ∇̄Ψ(qⁿ, q^{n+1}),
//     ∇̄Ψ = ∇Ψ(q^{n+½}) + β C (q^{n+1} − qⁿ),
//     β = [Ψ(q^{n+1}) − Ψ(qⁿ) − ∇Ψ(q^{n+½})·Δq] / |Δq|²_C            (Gonzalez's correction)
// has ∇̄Ψ·Δq = Ψ(q^{n+1}) − Ψ(qⁿ), hence H^{n+1} = Hⁿ exactly, through impacts, with the
// constraint exact at every full step (no penalty).  ∇Ψ(q^{n+½}) is what the half-step
// midpoint QP computes; the correction is a mass term: in U,
//     Bᵀ(V^{n+1} − Vⁿ)/dt + A U^{n+½} + β M (U^{n+1} − Uⁿ) = L + Gᵀλ,   U^{n+½} ∈ K̄^h,
// so X = U^{n+½} solves the midpoint QP with S = (4c² + 2β) M + A and
// r = (4c² + 2β) M Uⁿ + 2c Bᵀ Vⁿ + L (c = 1/dt).  Ψ at the full steps comes from the
// reconstruction of eq. (14) (schemes/full_step.hpp).
//
// Solving it.  The kinetic energy change of a step is fixed by the kinematics alone,
//     ΔK = ½(V^{n+1} + Vⁿ)ᵀC(V^{n+1} − Vⁿ) = 8c² DᵀMD − 4c (BᵀVⁿ)ᵀD,   D = X − Uⁿ,
// so the step's energy error is ΔH = ΔK + Ψ(q^{n+1}) − Ψ(qⁿ), and the scheme is the
// pair (X, β) with X the solution of the corrected QP and ΔH = 0.  β = 0 first: where
// Ψ is quadratic on [qⁿ, q^{n+1}] (no switch of the active set) ΔH = 0 already and the
// step is plain midpoint.  Otherwise β₁ = ΔH₀/|Δq|²_C (Gonzalez's formula at β = 0) and
// secant steps on ΔH(β).  The correction is applied lagged, 2β M (X_lag − Uⁿ) moved to
// the right-hand side, so that every iteration solves the QP with the same matrix
// S = 4Mc² + A — the one the solver has factorized — instead of a new S per β; the lag
// contracts by |β|/(2c²) per iteration (measured on the membrane: |β| ≤ 460 against
// 2c² = 2e6), X_lag is the last X extrapolated to the new β (so that the lag's error is
// second order in the β step and the secant sees ΔH(β) nearly exactly), and the
// iteration stops when ΔH is below energy_tol times the energy size of its terms (its
// round-off floor) and the lag would move X by less than the QP tolerance.
//
// When the correction asks for |β| ≥ c² (a large dt against a stiff switch: the seed's
// membrane at n = 10, dt = 0.01 asks β = −4.8e4 against 2c² = 2e4, where the corrected
// QP (4c² + 2β)M + A would not even be convex) or the iteration does not settle, the
// step is taken as two steps of dt/2, each a discrete gradient step itself, and so on
// down to dt/2¹⁰: c² grows four times per halving while the defect's β does not, so
// the switch is resolved by a few substeps and J stays exact.  The substep matrix
// 4M/h² + A is factorized while the substeps last.  Below dt/2¹⁰ the step is refused
// with a NumericalError, never continued with an energy error.
//
// Data that depend on t (a load L(t), an obstacle that moves: K̄^h(t)) make Ψ = Ψ(q, t)
// and H is no longer conserved: dH/dt = ∂ₜΨ, the power of the load and of the obstacle.
// By the envelope theorem (Ψ is a minimum over W) ∂ₜΨ = −L'(t)·W + λ·∂ₜg at the
// minimizer, with λ the reaction and g the active bound; the step takes it at the
// midpoint, where the QP has both, with the data's increments over the step:
//     Δ_tΨ = −(L(t^{n+1}) − L(tⁿ))·U^{n+½} + λ·(g(t^{n+1}) − g(tⁿ))
// (problems/data_work.hpp), and the discrete gradient asks
// ∇̄Ψ·Δq = Ψ(q^{n+1}, t^{n+1}) − Ψ(qⁿ, tⁿ) − Δ_tΨ, so that H^{n+1} − Hⁿ = Δ_tΨ exactly, the discrete work of the data on the body
// (StepStats::external_work): a second-order quadrature of ∫ ∂ₜΨ dt, exact when L and g
// are affine in t and the active set does not change (then β = 0 and the step is plain
// midpoint, as without data in t).
//
// Rayleigh damping (schemes/damping.hpp) is the midpoint's force (α_M M + β_K A) δU/dt,
// δU = U^{n+1} − Uⁿ = 2D, on the right of the momentum equation (α_M, β_K: not
// Gonzalez's β): S and r gain 2c(α_M M + β_K A) and the same times Uⁿ, and the step
// is asked H^{n+1} − Hⁿ + W_d = Δ_tΨ with W_d = 4c (α_M DᵀMD + β_K DᵀAD), the damping's
// work, so that J + W_d is conserved exactly (docs/schemes.md, "Rayleigh damping").
#include <cmath>
#include <optional>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/problems/data_work.hpp"
#include "cdyn/schemes/full_step.hpp"
#include "cdyn/schemes/step_qp_scheme.hpp"

namespace cdyn {

namespace {

class DiscreteGradient final : public StepQPScheme {
 public:
  DiscreteGradient(const ConstrainedProblem& p, StepSolver& solver, double dt, const SchemeParameters& parameters,
                   FullStepReconstruction full_step)
      : StepQPScheme(p, solver, dt, 1.0, 4.0, parameters.condense, parameters.damping, 2.0),
        full_step_(std::move(full_step)),
        energy_tol_(parameters.energy_tol),
        tol_(parameters.tol),
        autonomous_(!has_data_in_t(p)) {}
  std::string name() const override { return "discrete_gradient"; }
  FullSteps full_steps() const override { return FullSteps::Reconstructed; }

  void initialize(State& s) override {
    s.U = full_step_(s.U, s.t);
    psi_ = p_.potential_energy(s.U, s.t);
    initialized_ = true;
  }

  // Ψ(qⁿ) is remembered, not recomputed: the same number bit for bit.
  SchemeMemory memory() const override {
    SchemeMemory m = StepQPScheme::memory();
    full_step_.store(m);
    m.numbers["psi"] = psi_;
    return m;
  }

  void restore(const SchemeMemory& m) override {
    StepQPScheme::restore(m);
    full_step_.restore(m);
    psi_ = m.number("psi");
    initialized_ = true;
  }

  StepStats step(State& s) override {
    if (!initialized_) initialize(s);
    StepStats stats;
    advance(s, dt_, 0, stats);
    set_step_length(dt_);  // back to the step's matrix after substeps
    return stats;
  }

 private:
  // s advanced by h, as one discrete gradient step or as two of h/2 (depth: halvings so far).
  void advance(State& s, double h, int depth, StepStats& stats) {
    if (try_step(s, h, stats)) return;
    if (depth >= kMaxHalvings)
      throw NumericalError("discrete_gradient: the energy correction did not converge even with steps of dt/" +
                           std::to_string(1 << kMaxHalvings) + " at t = " + to_text(s.t) +
                           ": reduce time.dt (with step solves by CG alone, which stop at the QP tolerance, the "
                           "energy may not reach time.energy_tol: raise it, or solve with the factor)");
    ++stats.substeps;
    advance(s, 0.5 * h, depth + 1, stats);
    advance(s, 0.5 * h, depth + 1, stats);
  }

  // One discrete gradient step of length h; false (s unchanged) when the correction does
  // not converge.
  // S = (4/h² + 2α_M/h) M + (1 + 2β_K/h) A: the step matrix of a step of length h.
  void set_step_length(double h) {
    set_factors(1.0 + 2.0 * damping_.beta / h, 4.0 * (dt_ / h) * (dt_ / h) + 2.0 * damping_.alpha * (dt_ / h) * dt_);
  }

  bool try_step(State& s, double h, StepStats& stats) {
    const double c = 1.0 / h;
    set_step_length(h);
    constrain_at(s.t + 0.5 * h);  // U^{n+½} ∈ K̄^h(t^{n+½})
    // (4c² + 2α_M c) M Uⁿ + 2c Bᵀ Vⁿ + 2β_K c A Uⁿ + L
    Eigen::VectorXd r0 = inertia(4 * c * c + 2 * damping_.alpha * c, s.U, 2 * c, s.V) + p_.load(s.t + 0.5 * h);
    if (damping_.beta > 0.0) r0 += 2 * damping_.beta * c * symmetric_times(p_.A, s.U);
    const Eigen::VectorXd BtV = p_.mass->momentum(s.V);
    const double kinetic = p_.mass->kinetic_energy(s.V);
    const double t0 = s.t, t1 = s.t + h;
    DataIncrement data;
    if (!autonomous_) data = data_increment(p_, t0, t1);
    State trial_state = s;

    // One iteration: the QP with the correction −2β M (X_prev − Uⁿ) on the right, where
    // MD_prev = M (X_prev − Uⁿ) comes from the iterates (M is linear: the lag's product
    // is the same combination of theirs as X_prev of their X, no product of its own).
    struct Iterate {
      double beta = 0, dH = 0, psi1 = 0, dq2 = 0, terms = 0, work = 0, dissipated = 0;
      Eigen::VectorXd X, U1, W1, reaction;
      Eigen::VectorXd MD;     // M (X − Uⁿ)
      Eigen::VectorXd X_lag;  // the X of the lagged correction (empty: none)
    };
    auto iterate = [&](double beta, const Eigen::VectorXd* X_prev, const Eigen::VectorXd* MD_prev) {
      StepStats qp;
      Iterate it;
      it.beta = beta;
      it.X = solve(X_prev ? Eigen::VectorXd(r0 - 2 * beta * *MD_prev) : r0, trial_state, qp);
      if (X_prev) it.X_lag = *X_prev;
      stats.qp_iterations += qp.qp_iterations;
      stats.qp_seconds += qp.qp_seconds;
      stats.active = qp.active;
      stats.kkt_residual = std::max(stats.kkt_residual, qp.kkt_residual);
      ++stats.energy_iterations;
      const Eigen::VectorXd D = it.X - s.U;
      it.MD = mass_times(D);
      it.U1 = 2.0 * it.X - s.U;
      double kkt = 0.0;
      it.W1 = full_step_(it.U1, t1, &kkt);
      stats.reconstruction_kkt = std::max(stats.reconstruction_kkt, kkt);
      it.psi1 = p_.potential_energy(it.W1, t1);
      it.reaction = trial_state.reaction;
      if (!autonomous_) it.work = data.work(p_, it.X, it.reaction);
      const double DMD = D.dot(it.MD);
      it.dq2 = 4 * DMD;  // |Δq|²_C = ΔUᵀ M ΔU
      const double pull = 4 * c * BtV.dot(D);
      it.dissipated = damping_work(2.0 * D, h);  // W_d = 4c (α_M DᵀMD + β_K DᵀAD)
      it.dH = 8 * c * c * DMD - pull + it.dissipated + it.psi1 - psi_ - it.work;  // H^{n+1} + W_d − Hⁿ − Δ_tΨ
      // the size of what ΔH cancels: its round-off is a few ε of this
      it.terms = kinetic + 8 * c * c * DMD + std::abs(pull) + it.dissipated + std::abs(it.psi1) + std::abs(psi_) +
                 std::abs(it.work);
      return it;
    };
    auto small_energy = [&](const Iterate& it) { return std::abs(it.dH) <= energy_tol_ * it.terms; };
    // The next β: the secant through the last two iterates, where its slope is that of
    // Gonzalez's model ΔH(β) ≈ ΔH(β_b) − (β − β_b)|Δq|²_C within a factor 10; else the
    // model's own root.  Near the root the two ΔH are round-off and their secant slope is
    // noise: measured on the P2/P1 bar at t = 2, a secant step from β = −7.588 to
    // −9580, which sent the step into substeps.
    auto secant = [&](const Iterate& a, const Iterate& b) {
      const double model = b.dq2 > 0 ? b.beta + b.dH / b.dq2 : b.beta;
      if (b.beta == a.beta || b.dH == a.dH) return model;
      const double slope = (b.dH - a.dH) / (b.beta - a.beta);
      if (!(slope < -0.1 * b.dq2 && slope > -10 * b.dq2)) return model;
      return b.beta - b.dH / slope;
    };
    // The lag is resolved when one more iteration would move X by less than the QP
    // tolerance: the lag contracts by |β|/(2c²) (S = 4c²M + A against the correction
    // 2βM), so the next move is at most that times the last one.  (Asking the last move
    // itself to be below the tolerance fails when the step solves are inexact to their
    // tolerance — pdas's CG while the active set moves, or the CG path — whose noise in X
    // does not contract.)
    auto settled = [&](const Iterate& it) {
      const double scale = std::max(it.X.lpNorm<Eigen::Infinity>(), 1e-300);
      return it.X_lag.size() == 0 ||
             std::abs(it.beta) / (2 * c * c) * (it.X - it.X_lag).lpNorm<Eigen::Infinity>() <= tol_ * scale;
    };

    Iterate a = iterate(0.0, nullptr, nullptr);
    if (!small_energy(a)) {
      Iterate b = iterate(a.dq2 > 0 ? a.dH / a.dq2 : 0.0, &a.X, &a.MD);
      for (int k = 0; !(small_energy(b) && settled(b)); ++k) {
        // the lag contracts by |β|/(2c²): at |β| ≥ c² it no longer pays (or diverges)
        if (k >= kMaxIterations || !(std::abs(b.beta) < c * c)) return false;
        // the secant on ΔH(β) (β kept once ΔH is small: only the lag is left to settle)
        const double next = small_energy(b) ? b.beta : secant(a, b);
        // The lag is taken at X extrapolated to the new β along the last two iterates,
        // X_b + (β − β_b)(X_b − X_a)/(β_b − β_a): its error is then second order in the
        // β step instead of first, and ΔH at the new iterate is nearly ΔH(β) itself, on
        // which the secant converges superlinearly.
        Eigen::VectorXd X_lag = b.X, MD_lag = b.MD;
        if (b.beta != a.beta) {
          const double k = (next - b.beta) / (b.beta - a.beta);
          X_lag += k * (b.X - a.X);
          MD_lag += k * (b.MD - a.MD);
        }
        Iterate c_it = iterate(next, &X_lag, &MD_lag);
        a = std::move(b);
        b = std::move(c_it);
      }
      a = std::move(b);
    }
    s.V = 2.0 * p_.mass->velocity(c * (a.U1 - s.U)) - s.V;
    s.U = std::move(a.W1);
    s.reaction = std::move(a.reaction);
    s.t += h;
    psi_ = a.psi1;
    stats.external_work = stats.external_work.value_or(0.0) + a.work;
    stats.dissipated += a.dissipated;
    return true;
  }

  static constexpr int kMaxIterations = 30;
  static constexpr int kMaxHalvings = 10;
  FullStepReconstruction full_step_;
  double energy_tol_, tol_;
  bool autonomous_;  // neither L nor K̄^h depends on t: Ψ = Ψ(q), H conserved
  bool initialized_ = false;
  double psi_ = 0.0;  // Ψ(qⁿ): the potential energy of the reconstructed Uⁿ
};

}  // namespace

std::unique_ptr<TimeScheme> make_discrete_gradient(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                   const SchemeParameters& parameters) {
  if (!(parameters.energy_tol > 0)) throw InputError("energy_tol", "must be positive");
  // The reconstruction by the factor and its row updates, no CG, unless the run is on the
  // CG path: the energy iteration reconstructs nearly the same U^{n+1} several times in a
  // switching step, each with the active set of the last, where one solve with a factor
  // brought to that set costs less than CG's loose and tight pair (measured on the
  // published table's membrane at dt = 0.01 and 0.004, five interleaved runs: 7–9 % less
  // time a step at N_X = 40, 3.5 % at N_X = 20, none at 10 and at n = 160; the energy
  // iterations unchanged; docs/performance.md).  The midpoint's one
  // reconstruction a step meets a new set every step and keeps CG (20 % slower without).
  FullStepReconstruction full_step(p, parameters.tol, false,
                                   parameters.reconstruct_by_cg ? FullStepReconstruction::Solves::CgOnly
                                                                : FullStepReconstruction::Solves::Direct);
  // The scheme is the Hamiltonian system in q: it needs the massless part to be
  // determined by (14) (the seed's condition (12)).  Without massless directions (Ker B =
  // {0}: P1/P1, P1/P0, consistent, lumped) the constrained unknowns carry inertia, the
  // semi-discrete problem is not a Lipschitz ODE and Ψ is not differentiable.
  if (!full_step.available())
    throw InputError("scheme", "discrete_gradient needs the full steps of eq. (14), and a constrained unknown of " +
                                   p.mass->name() + " carries mass (condition (12) fails in local form)");
  if (!full_step.needed())
    throw InputError("scheme", "discrete_gradient needs a pair whose constrained unknowns are massless (condition "
                               "(12): P1+/P0, P1+/P1, P2/P1 or the redistributed mass), not " + p.mass->name() +
                               ", whose Ker B = {0}");
  return std::make_unique<DiscreteGradient>(p, solver, dt, parameters, std::move(full_step));
}

}  // namespace cdyn
