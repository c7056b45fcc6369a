// full_step.cpp — eq. (14) solved for the massless part of a full-step state.
#include "cdyn/schemes/full_step.hpp"

#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

namespace {

// The flags of the unknowns that carry a finite bound.
std::vector<char> bounded(const ConstrainedProblem& p) {
  std::vector<char> b(p.n_free(), 0);
  for (int i = 0; i < p.n_free(); ++i) b[i] = std::isfinite(p.lower[i]) || std::isfinite(p.upper[i]);
  return b;
}

}  // namespace

FullStepReconstruction::FullStepReconstruction(const ConstrainedProblem& p, double tol) : p_(p) {
  std::optional<MasslessModes> modes =
      massless_modes(p.mass->saddle(SparseMatrix(p.n_free(), p.n_free()), 1.0).B, bounded(p));
  if (!modes) return;
  available_ = true;
  modes_ = std::move(*modes);
  const std::vector<char> b = bounded(p);
  std::vector<char> pinned(p.n_free(), 0);
  for (int j : modes_.pinned) pinned[j] = 1;
  if (!needed()) return;
  // A constrained unknown that Ker B cannot move: (14) cannot enforce its bound, the
  // constraint acts on the massful part (condition (12) fails there).
  for (int i = 0; i < p.n_free(); ++i)
    if (b[i] && !pinned[i]) {
      available_ = false;
      return;
    }
  const SparseMatrix& Z = modes_.Z;
  qp_.S = SparseMatrix(Z.transpose()) * (p.A * Z);
  qp_.S = 0.5 * (qp_.S + SparseMatrix(qp_.S.transpose()));  // exact symmetry
  qp_.S.makeCompressed();
  Zt_ = transposed(Z);
  const int m = static_cast<int>(Z.cols());
  qp_.lower = Eigen::VectorXd::Constant(m, -std::numeric_limits<double>::infinity());
  qp_.upper = Eigen::VectorXd::Constant(m, std::numeric_limits<double>::infinity());
  QPOptions options;
  options.tol = tol;
  solver_ = make_step_solver("pdas", options);
}

Eigen::VectorXd FullStepReconstruction::operator()(const Eigen::VectorXd& U, double t, double* kkt) {
  if (!available_)
    throw InputError("scheme", "the massless displacements Ker B of " + p_.mass->name() +
                                   " have no local basis: the full-step state of eq. (14) cannot be reconstructed");
  if (!needed()) {
    if (kkt) *kkt = 0.0;
    return U;
  }
  const SparseMatrix& Z = modes_.Z;
  qp_.r = transpose_times(Z, p_.load(t) - symmetric_times(p_.A, U));
  const Eigen::VectorXd* lower = &p_.lower;
  const Eigen::VectorXd* upper = &p_.upper;
  Eigen::VectorXd lower_t, upper_t;
  if (!p_.bounds_are_constant()) {  // K̄^h(t) of a moving obstacle
    p_.bounds(t, lower_t, upper_t);
    lower = &lower_t, upper = &upper_t;
  }
  for (std::size_t k = 0; k < modes_.pinned.size(); ++k) {
    const int i = modes_.pinned[k];
    qp_.lower[k] = (*lower)[i] - U[i];
    qp_.upper[k] = (*upper)[i] - U[i];
  }
  last_ = solver_->solve(qp_, has_last_ ? &last_ : nullptr);
  has_last_ = true;
  if (kkt) *kkt = last_.kkt_residual;
  return U + transpose_times(Zt_, last_.X);
}

void FullStepReconstruction::store(SchemeMemory& m) const { store_warm_start(m, "full_step", last_, has_last_); }

void FullStepReconstruction::restore(const SchemeMemory& m) {
  if (solver_) solver_->clear();
  has_last_ = load_warm_start(m, "full_step", last_);
}

}  // namespace cdyn
