// step_qp_scheme.hpp — what the one-step implicit schemes share.
//
// Backward Euler and the two midpoint variants all solve, per step, a QP with
//     S = a A + k M,   k = m / dt²,
// (a, m) = (1, 1), (1, 4) and (½, 2) respectively, and differ only in r and in the
// update.  Rayleigh damping (schemes/damping.hpp) adds (αM + βA) δU/dt to a step whose
// increment is δU = U^{n+1} − Uⁿ = s (X − Uⁿ) (s = 1 with X = U^{n+1}, 2 with
// X = U^{n+½}): a += sβ/dt, m += sα dt, and r gains (s/dt)(αM + βA) Uⁿ.  This base class builds S once (explicitly when M is sparse — H^h = P0, the
// classical models, and H^h = W^h where B = C gives M = C — in saddle form otherwise), keeps the step solver's warm start, and provides M·x for the right-hand
// sides.
//
// Static condensation (qp/condensation.hpp).  With an explicit S, the unbounded unknowns
// whose block of S is block diagonal and whose elimination makes no fill — the bubbles
// of P1+/P0, each cell's as one block (bubble_unknowns: one unknown a component) — are
// eliminated once, when S is built: the solver sees the QP on the kept unknowns,
// S_c = S_vv − S_vb S_bb⁻¹ S_bv, r_c = r_v − S_vb S_bb⁻¹ r_b, and each step ends with the
// back-substitution X_b = S_bb⁻¹ (r_b − S_bv X_v).  The same QP, a third of the unknowns
// for P1+/P0 in the plane, a seventh on the unit cube's tetrahedra; the stats
// (iterations, KKT residual) are those of the condensed
// QP.  SchemeParameters::condense = false solves the full QP instead.
//
// Friction (problems/friction.hpp).  When the problem has friction nodes, the step is
// the frictional problem (FQP) of qp/friction_qp.hpp with the reference X̂ = Uⁿ: its
// slip X_T − Uⁿ_T is the step's tangential increment divided by s (s = 1 for the schemes
// that take friction: backward Euler and midpoint_end, X = U^{n+1}).  It is solved by
// projected Gauss–Seidel when the step solver is pgs, by Ipopt on split slip variables
// when it is ipopt (explicit S; qp/friction_ipopt.hpp), else by the semismooth Newton
// method around the step solver (qp/friction_solvers.hpp), to the scheme's tol.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cdyn/qp/condensation.hpp"
#include "cdyn/qp/friction_qp.hpp"
#include "cdyn/schemes/time_scheme.hpp"

namespace cdyn {

class StepQPScheme : public TimeScheme {
 public:
  // J(Uⁿ, Vⁿ) = ½ Vᵀ C V + ½ UᵀAU − LᵀU of the full field.
  Energy energy(const State& s) const override;
  // The step QP's warm start and whether its bubbles are still condensed; the schemes
  // add what they remember.
  SchemeMemory memory() const override;
  void restore(const SchemeMemory& m) override;

 protected:
  // (a, m): the undamped scheme's factors; the damping's share is added here for a step
  // whose increment is s (X − Uⁿ).
  StepQPScheme(const ConstrainedProblem& p, StepSolver& solver, double dt, double a, double m, bool condense = true,
               const RayleighDamping& damping = {}, double s = 1.0, double friction_tol = 1e-10);

  // M x = Bᵀ (C⁻¹ B x): the momentum of the velocity of x, by the same route as inertia()
  // below (not the explicit M, which has more entries than B and Bᵀ together for P1+/P0).
  Eigen::VectorXd mass_times(const Eigen::VectorXd& x) const;

  // The inertia terms of a right-hand side, a M U + b Bᵀ V = Bᵀ (a C⁻¹B U + b V): the
  // momentum of the velocity a C⁻¹B U + b V.  One product with B and one with Bᵀ (for
  // P1+/P0 together 40 % fewer entries than M and Bᵀ: M couples each vertex with its
  // 6 neighbours and 6 bubbles, B each triangle with 4 dofs); for the classical models
  // (velocity = U, momentum = M V) one product with M instead of two.
  Eigen::VectorXd inertia(double a, const Eigen::VectorXd& U, double b, const Eigen::VectorXd& V) const;

  // Solves the step QP with right-hand side r; fills s.reaction and the stats.
  Eigen::VectorXd solve(const Eigen::VectorXd& r, State& s, StepStats& stats);

  // The last solve's solution, reaction, right-hand side and held unknowns, in the
  // QP's own (condensed) numbering.
  struct Point {
    Eigen::VectorXd X, reaction, r;
    std::vector<int> active;
  };
  Point last_point() const { return {last_.X, last_.reaction, qp_.r, last_.active}; }
  // The step QP with the right-hand side r = r_a + θ (r_b − r_a), solved without a solve:
  // S fixed, the solution on an active set and its reaction S X − r are affine in r, so
  // the interpolate of two points solved on the same set is this r's solution wherever
  // it keeps that set and passes the solvers' own test (kkt_residual ≤ tol).  Returns X
  // (and sets s.reaction and the stats as solve() does), or nothing when the test fails
  // (or with friction, whose step is not one QP).
  std::optional<Eigen::VectorXd> on_line(const Point& a, const Point& b, double theta, const Eigen::VectorXd& r,
                                         double tol, State& s, StepStats& stats);

  // The bounds of the step QP (the problem's K̄^h unless a scheme moves them).  A finite
  // bound on a condensed unknown ends the condensation for the rest of the run.
  void set_bounds(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);

  // The step QP's bounds made K̄^h(t) of a moving obstacle (nothing to do when the
  // problem's bounds are constant): t is the time level the scheme constrains.
  void constrain_at(double t);

  // A vector the scheme keeps from the steps before (U^{n−1}, Newmark's V̇ⁿ), empty
  // before the first step: memory() stores it under `name` and restore() reads it back.
  // (The vector must live as long as the scheme: a member.)
  void remember(const std::string& name, Eigen::VectorXd* v) { remembered_.emplace_back(name, v); }

  // The explicit M when the mass model has one (H^h = P0, classical models), or C when B = C.
  const std::optional<SparseMatrix>& explicit_mass() const { return M_; }

  // S = aA + (m/dt²) M with other factors (the bounds back to the problem's K̄^h): a
  // new S for the solver, which then factorizes it again.  Nothing when they are the
  // current ones.
  void set_factors(double a, double m);

  // The work of the damping force (αM + βA) δU/h over a step of length h whose
  // increment is δU: W_d = (α δUᵀMδU + β δUᵀAδU)/h ≥ 0 (0 without damping).
  double damping_work(const Eigen::VectorXd& dU, double h) const;

  // Whether the step is (FQP): the problem has friction nodes (on a share of the QP, on
  // any rank's cells).
  bool with_friction() const { return with_friction_; }

  // x on the problem's free unknowns with those another rank owns set to 0 (on a share
  // of the QP, StepSolver::owns; a condensed bubble is its cell's rank's): summed over
  // the ranks, a sum over unknowns counts each once.  x itself on one process.
  Eigen::VectorXd owned_part(const Eigen::VectorXd& x) const;

  const ConstrainedProblem& p_;
  StepSolver& solver_;
  double dt_;
  const RayleighDamping damping_;

 private:
  void build(double a, double m);
  void end_condensation();  // the full QP from now on
  void map_friction();      // the friction nodes' unknowns in the step QP's numbering
  void tell_unknowns();     // the QP's unknowns to the solver (StepSolver::set_unknowns)
  void solve_with_friction(State& s, StepStats& stats);  // fills friction_last_
  Eigen::VectorXd report_last(const Eigen::VectorXd& r, State& s, StepStats& stats) const;

  double a_ = 0.0, m_ = 0.0;
  bool condense_;
  std::optional<SparseMatrix> M_;
  std::optional<StaticCondensation> condensation_;
  BoundQP qp_;
  Eigen::VectorXd D_;  // scaling_diagonal(qp_) for on_line, made on first use after a new S
  QPResult last_;
  bool has_last_ = false;
  std::vector<std::pair<std::string, Eigen::VectorXd*>> remembered_;
  // friction: the conditions on the QP's unknowns, the last result (the warm start),
  // the step's increment per unit slip (s), the tolerance
  FrictionConditions friction_;
  FrictionResult friction_last_;
  bool has_friction_last_ = false;
  bool with_friction_ = false;  // the problem has friction nodes (on any rank)
  double slip_factor_ = 1.0, friction_tol_ = 1e-10;
};

}  // namespace cdyn

namespace cdyn {
// The schemes built on StepQPScheme (one file each).
// condense: see StepQPScheme (static condensation of the bubbles).
std::unique_ptr<TimeScheme> make_backward_euler(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                const SchemeParameters& parameters = {});
std::unique_ptr<TimeScheme> make_midpoint(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                          const SchemeParameters& parameters);
std::unique_ptr<TimeScheme> make_midpoint_end(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                              const SchemeParameters& parameters);
std::unique_ptr<TimeScheme> make_discrete_gradient(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                   const SchemeParameters& parameters);
std::unique_ptr<TimeScheme> make_newmark(const ConstrainedProblem& p, StepSolver& solver, double dt, double beta,
                                         double gamma, bool condense = true);
std::unique_ptr<TimeScheme> make_paoli_schatzman(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                 double restitution);
std::unique_ptr<TimeScheme> make_energy_conserving(const ConstrainedProblem& p, StepSolver& solver, double dt,
                                                   bool condense = true);
}  // namespace cdyn
