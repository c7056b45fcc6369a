// full_step.cpp — eq. (14) solved for the massless part of a full-step state.
#include "cdyn/schemes/full_step.hpp"

#include <cmath>
#include <algorithm>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/base/scope_timer.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/qp/kkt.hpp"

namespace cdyn {

namespace {

// The flags of the unknowns that carry a finite bound.
std::vector<char> bounded(const ConstrainedProblem& p) {
  std::vector<char> b(p.n_free(), 0);
  for (int i = 0; i < p.n_free(); ++i) b[i] = std::isfinite(p.lower[i]) || std::isfinite(p.upper[i]);
  return b;
}

}  // namespace

FullStepReconstruction::FullStepReconstruction(const ConstrainedProblem& p, double tol)
    : FullStepReconstruction(p, tol, false) {}

FullStepReconstruction::FullStepReconstruction(const ConstrainedProblem& p, double tol, bool multipliers,
                                               Solves solves, const StepSolver* step)
    : p_(p), tol_(tol) {
  QPOptions options;
  options.tol = tol;
  solver_ = make_step_solver("pdas", options);
  if (p.mass->is_invertible()) {  // Ker B = {0}: nothing to reconstruct
    method_ = Method::LocalBasis;
    return;
  }
  const std::vector<char> b = bounded(p);
  const SparseMatrix B = p.mass->saddle(SparseMatrix(p.n_free(), p.n_free()), 1.0).B;
  std::optional<MasslessModes> modes = multipliers ? std::nullopt : massless_modes(B, b);
  if (!modes) {
    // (the pairs: their velocity() is C⁻¹B and momentum() Bᵀ, which the method uses; a
    // classical model's saddle factors are internal)
    if (!p.mass->velocity_is_rate()) method_ = Method::Multipliers;
    // (its saddle-form QPs are not split over subdomains: only the local basis's is)
    if (method_ == Method::Multipliers && step && step->solves_a_share())
      throw InputError("scheme", "the full-step reconstruction of " + p.mass->name() +
                                     " (by multipliers) does not run on subdomains yet");
    return;
  }
  modes_ = std::move(*modes);
  method_ = Method::LocalBasis;
  if (!needed()) return;
  // A constrained unknown that Ker B cannot move: (14) cannot enforce its bound, the
  // constraint acts on the massful part (condition (12) fails there).
  std::vector<char> pinned(p.n_free(), 0);
  for (int j : modes_.pinned) pinned[j] = 1;
  for (int i = 0; i < p.n_free(); ++i)
    if (b[i] && !pinned[i]) {
      method_ = Method::None;
      return;
    }
  const SparseMatrix& Z = modes_.Z;
  qp_.S = SparseMatrix(Z.transpose()) * (p.A * Z);
  qp_.S = 0.5 * (qp_.S + SparseMatrix(qp_.S.transpose()));  // exact symmetry
  qp_.S.makeCompressed();
  qp_.matrices_id = new_matrices_id();
  D_ = scaling_diagonal(qp_);  // the D of pdas's own rule
  Zt_ = transposed(Z);
  const int m = static_cast<int>(Z.cols());
  qp_.lower = Eigen::VectorXd::Constant(m, -std::numeric_limits<double>::infinity());
  qp_.upper = Eigen::VectorXd::Constant(m, std::numeric_limits<double>::infinity());
  if (solves != Solves::Mixed) {
    options.pdas_cg_only = solves == Solves::CgOnly;
    if (solves == Solves::Direct) options.pdas_cg_iterations = 0;
    solver_ = make_step_solver("pdas", options);
  }
  // A share of the step QP (each rank its cells): ZᵀAZ and Zᵀ(L − AU) are sums over cells
  // too (Z's column of a vertex moves the bubbles of its cells only), and the ranks solve
  // their sum together
  if (std::unique_ptr<StepSolver> companion = step ? step->make_companion(options) : nullptr) {
    solver_ = std::move(companion);
    solver_->set_unknowns(modes_.pinned);
  }
}

void FullStepReconstruction::prepare_multipliers() {
  SaddleForm form = p_.mass->saddle(p_.A, 1.0);
  // ρ = 10³ ω²_max, ω²_max estimated by the largest ratio A_jj / M_jj with the diagonal
  // M_jj ≈ Σ_k B_kj² / C_kk (qp/kkt.hpp's scaling): the stiffest free unknown's
  // frequency, within the factor of the element's Rayleigh quotients.
  const Eigen::VectorXd Cd = form.C.diagonal();
  Eigen::VectorXd m = Eigen::VectorXd::Zero(p_.n_free());
  for (int k = 0; k < form.B.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(form.B, k); it; ++it) m[it.col()] += it.value() * it.value() / Cd[it.row()];
  A_diagonal_ = p_.A.diagonal();
  double omega2 = 0.0;
  for (int j = 0; j < p_.n_free(); ++j)
    if (m[j] > 0) omega2 = std::max(omega2, A_diagonal_[j] / m[j]);
  if (!(omega2 > 0))
    throw NumericalError("full-step reconstruction (eq. 14): no unknown has both mass and stiffness");
  rho_ = 1e3 * omega2;
  // A + ρ Bᵀ C⁻¹ B as the saddle form {A, √ρ B, C, 1}: its blocks [[A, √ρ Bᵀ],
  // [√ρ B, −C]] are of comparable size, where {A, B, C, ρ} (ρ ~ 1e7 … 1e13) made UMFPACK
  // pivot away from its fill-reducing order (measured on the membrane at n = 40, P2/P1,
  // dt = 0.001: 18.3–19.8 against 47–49 ms a step of the reconstructed midpoint).
  form.B *= std::sqrt(rho_);
  form.c = 1.0;
  qp_.saddle = std::move(form);
  qp_.matrices_id = new_matrices_id();
  qp_.lower.resize(p_.n_free());
  qp_.upper.resize(p_.n_free());
  all_unknowns_.resize(p_.n_free());
  for (int i = 0; i < p_.n_free(); ++i) all_unknowns_[i] = i;
}

void FullStepReconstruction::set_bounds(const Eigen::VectorXd& U, const std::vector<int>& unknowns, double t) {
  const Eigen::VectorXd* lower = &p_.lower;
  const Eigen::VectorXd* upper = &p_.upper;
  Eigen::VectorXd lower_t, upper_t;
  if (!p_.bounds_are_constant()) {  // K̄^h(t) of a moving obstacle
    p_.bounds(t, lower_t, upper_t);
    lower = &lower_t, upper = &upper_t;
  }
  for (std::size_t k = 0; k < unknowns.size(); ++k) {
    const int i = unknowns[k];
    qp_.lower[k] = (*lower)[i] - U[i];
    qp_.upper[k] = (*upper)[i] - U[i];
  }
}

Eigen::VectorXd FullStepReconstruction::operator()(const Eigen::VectorXd& U, double t, double* kkt) {
  if (!available())
    throw InputError("scheme", "the massless displacements Ker B of " + p_.mass->name() +
                                   " cannot be reconstructed: a constrained unknown carries mass (condition (12) "
                                   "fails in local form)");
  cost_ = Cost{};
  if (!needed()) {  // (Ker B = {0}: nothing done, nothing to count)
    if (kkt) *kkt = 0.0;
    return U;
  }
  const ScopeTimer timer(cost_.seconds);
  return method_ == Method::LocalBasis ? by_local_basis(U, t, kkt) : by_multipliers(U, t, kkt);
}

Eigen::VectorXd FullStepReconstruction::by_local_basis(const Eigen::VectorXd& U, double t, double* kkt) {
  const SparseMatrix& Z = modes_.Z;
  Eigen::VectorXd r = transpose_times(Z, evaluated(p_.load(t) - symmetric_times(p_.A, U)));
  set_bounds(U, modes_.pinned, t);
  // The warm start's active set: the PDAS rule at the last solution with this step's
  // bounds and force, not the last active set itself.  The massful part moves the data
  // every step (a lifting membrane frees a ring of vertices a step), and the last set
  // starts the iteration one ring behind: 3.9 → 2.1 PDAS iterations a step on the
  // lifting membrane (docs/performance.md).  (The step QP keeps the last set: its
  // unknown moves by V dt between steps, and the rule at the last X mispredicts there.)
  if (has_last_) {
    if (SX_.size() != last_.X.size()) SX_ = symmetric_times(qp_.S, last_.X);
    last_.active = active_set(qp_, last_.X, SX_ - r, D_);
  }
  qp_.r = std::move(r);
  last_ = solver_->solve(qp_, has_last_ ? &last_ : nullptr);
  has_last_ = true;
  cost_.qp_iterations = last_.iterations;
  SX_ = last_.reaction + qp_.r;  // S X (the reaction is S X − r)
  if (kkt) *kkt = last_.kkt_residual;
  return evaluated(U + transpose_times(Zt_, last_.X));
}

FullStepReconstruction::Point FullStepReconstruction::last_point() const {
  if (method_ != Method::LocalBasis || !has_last_) return {};
  return {last_.X, last_.reaction, qp_.r, last_.active};
}

std::optional<Eigen::VectorXd> FullStepReconstruction::on_line(const Point& a, const Point& b, double theta,
                                                               const Eigen::VectorXd& U, double t, double* kkt,
                                                               Point* at) {
  cost_ = Cost{};
  if (method_ != Method::LocalBasis || !needed() || a.y.size() != qp_.size() || b.y.size() != qp_.size())
    return std::nullopt;
  const ScopeTimer timer(cost_.seconds);
  auto along = [theta](const Eigen::VectorXd& p, const Eigen::VectorXd& q) {
    return Eigen::VectorXd(p + theta * (q - p));
  };
  Point p{along(a.y, b.y), along(a.reaction, b.reaction), along(a.r, b.r), b.active};
  set_bounds(U, modes_.pinned, t);
  hold_at_bounds(qp_, p.active, p.y);
  qp_.r = p.r;
  const double residual = kkt_residual(qp_, p.y, p.reaction, &D_);  // (exact on the points' set only)
  if (active_set(qp_, p.y, p.reaction, D_) != p.active || !(residual <= tol_)) return std::nullopt;
  if (kkt) *kkt = residual;
  Eigen::VectorXd W = U + transpose_times(Zt_, p.y);
  if (at) *at = std::move(p);
  return W;
}

Eigen::VectorXd FullStepReconstruction::by_multipliers(const Eigen::VectorXd& U, double t, double* kkt) {
  if (!qp_.saddle) prepare_multipliers();
  if (mu_.size() == 0) mu_ = Eigen::VectorXd::Zero(p_.mass->n_velocity());
  const Eigen::VectorXd f = p_.load(t) - symmetric_times(p_.A, U);
  set_bounds(U, all_unknowns_, t);
  const double force_scale = f.cwiseQuotient(A_diagonal_).lpNorm<Eigen::Infinity>();
  // The fibre's residual |C⁻¹ B D|∞ (a displacement, as D) is driven to 1e-14 of the
  // state, near round-off: Ψ's error is first order in it (the multiplier times the
  // residual), unlike the QP's, which is second order on the fibre, and the energy-exact
  // scheme asks Ψ to 1e-12 (time.energy_tol).  (4 ε instead took a third iteration
  // where two reach 1e-15.)  The state's scale is that of kkt_residual (qp/kkt.hpp):
  // |U|, |W| and the displacement the force L − AU would cause by itself,
  // |diag(A)⁻¹(L − AU)| (the one left for a body at rest).  The iteration stops there,
  // or when the residual no longer halves (round-off, or no solution).
  const double target = 1e-14;
  double residual = std::numeric_limits<double>::infinity(), scale = 0.0;
  iterations_ = 0;
  for (int k = 0; k < 100; ++k) {
    qp_.r = f + p_.mass->momentum(mu_);
    last_ = solver_->solve(qp_, has_last_ ? &last_ : nullptr);
    has_last_ = true;
    ++iterations_;
    cost_.qp_iterations += last_.iterations;
    const Eigen::VectorXd y = p_.mass->velocity(last_.X);  // C⁻¹ B D
    mu_ -= rho_ * y;
    const double previous = residual;
    residual = y.lpNorm<Eigen::Infinity>();
    scale = std::max({U.lpNorm<Eigen::Infinity>(), (U + last_.X).lpNorm<Eigen::Infinity>(), force_scale});
    if (residual <= target * scale || (k >= 3 && residual > 0.5 * previous)) break;
  }
  const double fibre = scale > 0 ? residual / scale : residual;
  if (!(fibre <= tol_))
    throw NumericalError("full-step reconstruction (eq. 14): the multipliers leave B W off B U by " +
                         to_text(fibre) + " of |W| after " + std::to_string(iterations_) +
                         " iterations (the constraints and B W = B U cannot both hold: condition (12))");
  if (kkt) *kkt = std::max(last_.kkt_residual, fibre);
  return U + last_.X;
}

void FullStepReconstruction::store(SchemeMemory& m) const {
  store_warm_start(m, "full_step", last_, has_last_);
  m.store_if_any("full_step.SX", SX_);
  m.store_if_any("full_step.multiplier", mu_);
}

void FullStepReconstruction::restore(const SchemeMemory& m) {
  if (solver_) solver_->clear();
  has_last_ = load_warm_start(m, "full_step", last_);
  SX_ = m.vector_or_empty("full_step.SX");
  mu_ = m.vector_or_empty("full_step.multiplier");
}

}  // namespace cdyn
