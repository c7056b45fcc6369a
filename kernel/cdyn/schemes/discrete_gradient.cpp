// discrete_gradient.cpp — an energy-exact full discretization of the singular dynamic
// method: a discrete gradient (Gonzalez 1996; McLachlan, Quispel and Robidoux 1999) of
// the reduced potential Ψ.
//
// Under condition (12), with q = C⁻¹B U the velocity-space coordinate of the massful
// part, the semi-discrete problem is the Hamiltonian system (docs/equations.md,
// Theorem 1 and eq. (14))
//     q̇ = V,   C V̇ = −∇Ψ(q),   Ψ(q) = min { ½WᵀAW − LᵀW : C⁻¹B W = q, W ∈ K̄^h },
// H = ½VᵀCV + Ψ(q) the seed's J, and Ψ convex with a Lipschitz gradient.  The scheme
//     q^{n+1} − qⁿ = dt V^{n+½},   C (V^{n+1} − Vⁿ) = −dt ∇̄Ψ,
//     ∇̄Ψ = ∇Ψ(q^{n+½}) + β C Δq₀,   β such that ∇̄Ψ·Δq = Ψ(q^{n+1}) − Ψ(qⁿ),
// Δq = q^{n+1} − qⁿ and Δq₀ the same increment of the uncorrected step (β = 0), has
// H^{n+1} = Hⁿ exactly, through impacts, with the constraint exact at every full step
// (no penalty).  ∇̄Ψ is a discrete gradient in McLachlan–Quispel–Robidoux's sense (the
// discrete chain rule, and consistent: β C Δq₀ is of the size of Gonzalez's β C Δq,
// whose direction Δq it takes at the step without correction).  ∇Ψ(q^{n+½}) is what the
// half-step midpoint QP computes; the correction is a mass term: in U,
//     Bᵀ(V^{n+1} − Vⁿ)/dt + A U^{n+½} + β M (U₀^{n+1} − Uⁿ) = L + Gᵀλ,   U^{n+½} ∈ K̄^h,
// so X = U^{n+½} solves the midpoint QP, S = 4c² M + A (c = 1/dt) for every β, with
// r = 4c² M Uⁿ + 2c Bᵀ Vⁿ + L − 2β d, d = M (X₀ − Uⁿ), X₀ the solution at β = 0.
// Ψ at the full steps comes from the reconstruction of eq. (14) (schemes/full_step.hpp).
//
// Solving it.  The kinetic energy change of a step is fixed by the kinematics alone,
//     ΔK = ½(V^{n+1} + Vⁿ)ᵀC(V^{n+1} − Vⁿ) = 8c² DᵀMD − 4c (BᵀVⁿ)ᵀD,   D = X − Uⁿ,
// so the step's energy error is ΔH(β) = ΔK + Ψ(q^{n+1}) − Ψ(qⁿ), a function of the one
// number β.  β = 0 first: where Ψ is quadratic on [qⁿ, q^{n+1}] (no switch of the
// active set) ΔH = 0 already and the step is plain midpoint.  Otherwise β₁ = ΔH₀/|Δq₀|²_C
// (Gonzalez's formula at β = 0), a secant step, then Muller's: on fixed active sets X
// is affine in β (S does not depend on it), so are U^{n+1} and its reconstruction, and
// ΔH(β) is a quadratic, which the parabola through the last three iterates finds
// exactly, every QP with the matrix the solver has already factorized.  Where two
// iterates were solved on the same active sets (of the step QP and of the
// reconstruction), the next one is not solved for: it is their interpolate, accepted
// by both QPs' own KKT test (StepQPScheme::on_line, FullStepReconstruction::on_line),
// so that a switching step takes two or three step QPs and reconstructions.  The
// iteration stops when ΔH is below energy_tol times the energy size of its terms (its
// round-off floor).  (Gonzalez's
// own correction β C Δq makes S = (4c² + 2β) M + A depend on β: a new factorization per
// iterate, or, on the right-hand side, a lag to iterate out at a contraction |β|/(2c²),
// which took 6–9 iterations a switching step where this takes 4: docs/schemes.md.)
//
// When the correction asks for |β| ≥ c² (a large dt against a stiff switch; the force
// 2β d would then undo more than half of the step's inertia 4c² M D₀) or the iteration
// does not converge, the step is taken as two steps of dt/2, each a discrete gradient
// step itself, and so on down to dt/2¹⁰: c² grows four times per halving while the
// defect's β does not, so the switch is resolved by a few substeps and J stays exact.
// The substep matrix 4M/h² + A is factorized while the substeps last.  Below dt/2¹⁰ the
// step is refused with a NumericalError, never continued with an energy error.
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
        autonomous_(solver.largest(has_data_in_t(p) ? 1.0 : 0.0) == 0.0) {}
  std::string name() const override { return "discrete_gradient"; }
  FullSteps full_steps() const override { return FullSteps::Reconstructed; }

  void initialize(State& s) override {
    s.U = full_step_(s.U, s.t);
    psi_ = whole(p_.potential_energy(s.U, s.t));
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
    const double kinetic = whole(p_.mass->kinetic_energy(s.V));
    const double t0 = s.t, t1 = s.t + h;
    DataIncrement data;
    if (!autonomous_) data = data_increment(p_, t0, t1);
    State trial_state = s;

    // One iteration: the QP with the correction −2β d on the right, d = M (X₀ − Uⁿ) the
    // direction of the uncorrected step (β = 0), the same for every β of the step.
    struct Iterate {
      double beta = 0, dH = 0, psi1 = 0, dq2 = 0, terms = 0, work = 0, dissipated = 0;
      double dissipated_here = 0;  // this rank's share of W_d (StepStats::dissipated)
      Eigen::VectorXd X, U1, W1, reaction;
      Eigen::VectorXd MD;                      // M (X − Uⁿ)
      StepQPScheme::Point qp;                  // the two QPs' solved points (on_line below)
      FullStepReconstruction::Point full_step;
    };
    // ΔH of an iterate whose X, M (X − Uⁿ), W1 and reaction are set.
    // (on a share of the QP each term is the sum of the ranks' sums over cells, the
    // reaction's work counted by the owners: every rank then takes the same decisions)
    auto evaluate = [&](Iterate& it) {
      it.psi1 = whole(p_.potential_energy(it.W1, t1));
      if (!autonomous_) it.work = whole(data.work(p_, it.X, owned_part(it.reaction)));
      const Eigen::VectorXd D = it.X - s.U;
      const double DMD = whole(D.dot(it.MD));
      it.dq2 = 4 * DMD;  // |Δq|²_C = ΔUᵀ M ΔU
      const double pull = whole(4 * c * BtV.dot(D));
      it.dissipated_here = damping_work(2.0 * D, h);  // W_d = 4c (α_M DᵀMD + β_K DᵀAD)
      it.dissipated = whole(it.dissipated_here);
      it.dH = 8 * c * c * DMD - pull + it.dissipated + it.psi1 - psi_ - it.work;  // H^{n+1} + W_d − Hⁿ − Δ_tΨ
      // the size of what ΔH cancels: its round-off is a few ε of this
      it.terms = kinetic + 8 * c * c * DMD + std::abs(pull) + it.dissipated + std::abs(it.psi1) + std::abs(psi_) +
                 std::abs(it.work);
    };
    // The two QPs' last solved points, for on_line.
    auto keep_points = [&](Iterate& it) {
      it.qp = last_point();
      it.full_step = full_step_.last_point();
    };
    // The last reconstruction's cost, added to the step's (a point on a line solves no QP).
    auto count_reconstruction = [&]() {
      stats.reconstruction_seconds += full_step_.last_cost().seconds;
      stats.reconstruction_iterations += full_step_.last_cost().qp_iterations;
    };
    // to_round_off: the solve by a factorization, not by CG to the QP tolerance (below).
    auto iterate = [&](double beta, const Eigen::VectorXd* d, bool to_round_off) {
      StepStats qp;
      Iterate it;
      it.beta = beta;
      if (d) solver_.next_in_same_step(to_round_off);  // (the step's β = 0 solve came first)
      it.X = solve(d ? Eigen::VectorXd(r0 - 2 * beta * *d) : r0, trial_state, qp);
      stats.qp_iterations += qp.qp_iterations;
      stats.qp_seconds += qp.qp_seconds;
      stats.active = qp.active;
      stats.kkt_residual = std::max(stats.kkt_residual, qp.kkt_residual);
      ++stats.energy_iterations;
      it.MD = mass_times(it.X - s.U);
      it.U1 = 2.0 * it.X - s.U;
      double kkt = 0.0;
      it.W1 = full_step_(it.U1, t1, &kkt);
      stats.reconstruction_kkt = std::max(stats.reconstruction_kkt, kkt);
      count_reconstruction();
      it.reaction = trial_state.reaction;
      if (d) keep_points(it);  // (β = 0's, only when the step switches: below)
      evaluate(it);
      return it;
    };
    // The iterate at β without a solve, where a and b were solved on the same active sets
    // (of the step QP and of the reconstruction): S is fixed and r affine in β, so the
    // step's X and reaction, and with them U^{n+1}, the reconstruction's bounds,
    // right-hand side, solution and reaction, are affine in β there; their interpolates
    // are the iterate at β wherever both QPs' own tests pass (StepQPScheme::on_line,
    // FullStepReconstruction::on_line).  Nothing otherwise: then β is solved for.
    // (Not on a share of the QP: the two QPs' tests read this rank's share only.)
    auto on_line = [&](const Iterate& a, const Iterate& b, double beta,
                       const Eigen::VectorXd& d) -> std::optional<Iterate> {
      if (solver_.solves_a_share() || a.beta == b.beta || a.full_step.y.size() == 0 || a.qp.active != b.qp.active ||
          a.full_step.active != b.full_step.active)
        return std::nullopt;  // (no points: (14) by multipliers)
      const double theta = (beta - a.beta) / (b.beta - a.beta);
      // a and b are exact to their solves' tolerance: a far extrapolation multiplies their
      // errors by |θ| + |1 − θ|; within θ ∈ [−1, 2] by at most 3, a solve's own accuracy
      if (!(std::abs(theta - 0.5) <= 1.5)) return std::nullopt;
      StepStats qp;
      std::optional<Eigen::VectorXd> X =
          StepQPScheme::on_line(a.qp, b.qp, theta, r0 - 2 * beta * d, tol_, trial_state, qp);
      if (!X) return std::nullopt;
      Iterate it;
      it.beta = beta;
      it.X = std::move(*X);
      it.U1 = 2.0 * it.X - s.U;
      double kkt = 0.0;
      std::optional<Eigen::VectorXd> W1 =
          full_step_.on_line(a.full_step, b.full_step, theta, it.U1, t1, &kkt, &it.full_step);
      count_reconstruction();
      if (!W1) return std::nullopt;
      stats.kkt_residual = std::max(stats.kkt_residual, qp.kkt_residual);
      stats.reconstruction_kkt = std::max(stats.reconstruction_kkt, kkt);
      it.W1 = std::move(*W1);
      it.MD = a.MD + theta * (b.MD - a.MD);
      it.reaction = trial_state.reaction;
      it.qp = last_point();  // the accepted interpolate (StepQPScheme::on_line keeps it)
      evaluate(it);
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

    // With three iterates, the root of the parabola through them (Muller's method): on
    // fixed active sets X, the reconstruction and hence ΔH are affine and quadratic in β,
    // so the parabola's root is the step's.  Taken only where it corrects the secant's
    // step by less than that step (away from a kink of ΔH, and not from round-off's
    // curvature).
    auto muller = [&](const Iterate& x0, const Iterate& x1, const Iterate& x2, double secant_root) {
      const double d01 = (x1.dH - x0.dH) / (x1.beta - x0.beta), d12 = (x2.dH - x1.dH) / (x2.beta - x1.beta);
      const double curvature = (d12 - d01) / (x2.beta - x0.beta);
      const double w = d12 + curvature * (x2.beta - x1.beta);
      const double disc = w * w - 4 * x2.dH * curvature;
      if (!(disc >= 0) || !std::isfinite(curvature)) return secant_root;
      const double q = w + std::copysign(std::sqrt(disc), w);
      if (q == 0) return secant_root;
      const double root = x2.beta - 2 * x2.dH / q;
      return std::abs(root - secant_root) <= std::abs(secant_root - x2.beta) ? root : secant_root;
    };

    Iterate a = iterate(0.0, nullptr, false);
    if (!small_energy(a)) {
      keep_points(a);  // (no solve since a's)
      const Eigen::VectorXd d = a.MD;
      Iterate b = iterate(a.dq2 > 0 ? a.dH / a.dq2 : 0.0, &d, false);
      std::optional<Iterate> z;  // the iterate before a
      bool interpolating = true;
      // An iterate that does not halve |ΔH| has met the solves' own errors (a solve by CG
      // stops at the QP tolerance, whose energy error may exceed energy_tol: measured on
      // the damped disk at tol = 1e-10, ΔH stuck at 6e-12 of its terms while β moved):
      // the step's next solves to round-off.
      bool to_round_off = !(std::abs(b.dH) <= 0.5 * std::abs(a.dH));
      for (int k = 0;; ++k) {
        // |β| ≥ c²: the correction 2β d would undo more than half of the step's inertia
        // 4c² M D₀ — the switch is too stiff for the step: halve it
        if (!(std::abs(b.beta) < c * c)) return false;
        if (small_energy(b)) break;
        if (k >= kMaxIterations) return false;
        double next = secant(a, b);
        if (z) next = muller(*z, a, b, next);
        // The interpolate, while interpolates make progress: where a and b differ by
        // little more than their solves' errors (a tiny β), the line is their noise and
        // its ΔH stalls; then the rest of the step is solved for.
        std::optional<Iterate> predicted;
        if (interpolating) predicted = on_line(a, b, next, d);
        if (predicted && !(std::abs(predicted->dH) <= 0.1 * std::abs(b.dH))) {
          predicted.reset();
          interpolating = false;
        }
        Iterate c_it = predicted ? std::move(*predicted) : iterate(next, &d, to_round_off);
        if (!(std::abs(c_it.dH) <= 0.5 * std::abs(b.dH))) to_round_off = true;
        z = std::move(a);
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
    stats.dissipated += a.dissipated_here;
    return true;
  }

  // A sum over cells (an energy, a work) of the whole problem: on a share, the ranks'
  // sums added.
  double whole(double x) const { return solver_.total(x); }

  static constexpr int kMaxIterations = 30;
  static constexpr int kMaxHalvings = 10;
  FullStepReconstruction full_step_;
  double energy_tol_;  // ΔH's, relative to its terms
  double tol_;         // the step QPs' (kkt_residual)
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
  // (Re-measured with the correction along the uncorrected step and the iterates on the
  // line: CG while the set moves gave the same time within 0.01–0.1 of the ratio to
  // midpoint in five cells, five interleaved runs each.)
  // (on a share of the step QP the ranks solve the reconstruction's together: the step
  // solver's companion)
  FullStepReconstruction full_step(p, parameters.tol, false,
                                   parameters.reconstruct_by_cg ? FullStepReconstruction::Solves::CgOnly
                                                                : FullStepReconstruction::Solves::Direct,
                                   &solver);
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
