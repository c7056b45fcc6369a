// friction_pgs.cpp — projected Gauss–Seidel for the frictional step problem: the exact
// minimizer of (FQP) along one unknown at a time, and a contact node's tangential
// unknowns (two in space) as one block (qp/friction_solvers.hpp).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/qp/friction_solvers.hpp"
#include "cdyn/qp/kkt.hpp"

namespace cdyn {

namespace {

// (S X − r)_i with the current X (S symmetric: column i is row i).
double gradient(const SparseMatrix& S, const Eigen::VectorXd& r, const Eigen::VectorXd& X, int i) {
  double g = -r[i];
  for (SparseMatrix::InnerIterator it(S, i); it; ++it) g += it.value() * X[it.row()];
  return g;
}

// The tangential block of a contact node (one or two unknowns): the minimizer of
//     ½ dᵀ S_TT d + gᵀ d + s |d|     majorized by     ½ L |d − d₀|² + g₀ᵀ (d − d₀) + s |d|,
// L = λ_max(S_TT) ≥ the block's curvature, which is  d = shrink(d₀ − g₀/L, s/L),
// shrink(y, τ) = max(0, 1 − τ/|y|) y — the exact minimizer along the unknown when the
// block is one unknown (L = S_tt), and a step that never increases (FQP) for two (a
// proximal gradient step on the block: Beck and Teboulle 2009).
void update_tangential_block(const SparseMatrix& S, const BoundQP& qp, const Eigen::VectorXd& reference,
                             const std::vector<int>& t, double s, Eigen::VectorXd& X) {
  const std::size_t m = t.size();
  double L = S.coeff(t[0], t[0]);
  if (m == 2) {  // λ_max of [[a, b], [b, c]]
    const double a = S.coeff(t[0], t[0]), b = S.coeff(t[0], t[1]), c = S.coeff(t[1], t[1]);
    L = 0.5 * (a + c) + std::hypot(0.5 * (a - c), b);
  }
  std::array<double, 2> y{};
  double norm = 0.0;
  for (std::size_t j = 0; j < m; ++j) {
    y[j] = X[t[j]] - reference[t[j]] - gradient(S, qp.r, X, t[j]) / L;
    norm += y[j] * y[j];
  }
  norm = std::sqrt(norm);
  const double factor = norm > s / L ? 1.0 - s / (L * norm) : 0.0;
  for (std::size_t j = 0; j < m; ++j) X[t[j]] = reference[t[j]] + factor * y[j];
}

}  // namespace

FrictionResult solve_friction_pgs(const BoundQP& qp, const FrictionConditions& f, const FrictionOptions& options,
                                  const FrictionResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  if (qp.saddle)
    throw InputError("pgs: projected Gauss-Seidel needs the entries of S, but the problem is given in saddle form; "
                     "use solver pdas or ipopt");
  check_friction_qp(qp, f);
  const int n = qp.size(), m = static_cast<int>(f.contacts.size());
  const int max_sweeps = options.max_iterations > 0 ? options.max_iterations : 100000;
  const int check_every = std::max(1, options.pgs_check_every);
  // role[i]: the contact whose first tangential unknown i is (its block is updated
  // there), −2 for the other tangential unknowns, −1 elsewhere
  std::vector<int> role(n, -1);
  for (int k = 0; k < m; ++k) {
    if (f.contacts[k].tangential.size() > 2)
      throw InputError("friction: pgs takes one or two tangential unknowns per contact node");
    role[f.contacts[k].tangential[0]] = k;
    for (std::size_t j = 1; j < f.contacts[k].tangential.size(); ++j) role[f.contacts[k].tangential[j]] = -2;
  }
  const SparseMatrix& S = qp.S;
  const Eigen::VectorXd diag = S.diagonal();
  for (int i = 0; i < n; ++i)
    if (!(diag[i] > 0.0)) throw NumericalError("friction (pgs): S is not positive definite (S_ii ≤ 0 at unknown " +
                                               std::to_string(i) + ")");

  Eigen::VectorXd X = f.reference;
  if (warm_start && warm_start->qp.X.size() == n) X = warm_start->qp.X;
  for (int i = 0; i < n; ++i) X[i] = std::clamp(X[i], qp.lower[i], qp.upper[i]);

  FrictionResult result;
  int sweep = 0;
  std::string detail;
  for (;;) {
    if (sweep % check_every == 0) {
      const Eigen::VectorXd reaction = S * X - qp.r;
      const Eigen::VectorXd s = friction_thresholds(f, reaction);
      result.residual = friction_residual(qp, f, X, reaction, s, diag);
      result.qp.reaction = reaction;
      result.threshold = s;
      result.converged = result.residual <= options.tol;
      if (result.converged) break;
      if (!std::isfinite(result.residual)) {
        detail = "the iterates are not finite";
        break;
      }
    }
    if (sweep >= max_sweeps) {
      detail = "maximum number of sweeps reached";
      break;
    }
    ++sweep;
    for (int i = 0; i < n; ++i) {
      const int k = role[i];
      if (k == -2) continue;  // in its node's block
      if (k == -1) {  // the unconstrained minimizer along e_i, projected on the box
        X[i] = std::clamp(X[i] - gradient(S, qp.r, X, i) / diag[i], qp.lower[i], qp.upper[i]);
        continue;
      }
      const FrictionContact& c = f.contacts[k];
      const double s = c.coulomb ? c.mu * std::max(gradient(S, qp.r, X, c.normal), 0.0) : c.threshold;
      update_tangential_block(S, qp, f.reference, c.tangential, s, X);
    }
  }
  result.qp.X = X;
  result.qp.iterations = sweep;
  result.qp.kkt_residual = result.residual;
  result.qp.converged = result.converged;
  result.qp.active = active_set(qp, X, result.qp.reaction, diag);
  result.status = contact_status(qp, f, X, result.qp.reaction);
  result.stick.assign(m, 1);
  result.direction = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < m; ++k) {
    const std::vector<int>& t = f.contacts[k].tangential;
    double norm = 0.0;
    for (int j : t) norm += (X[j] - f.reference[j]) * (X[j] - f.reference[j]);
    norm = std::sqrt(norm);
    result.stick[k] = norm == 0.0;
    if (norm != 0.0)
      for (int j : t) result.direction[j] = (X[j] - f.reference[j]) / norm;
  }
  result.qp.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result.converged && options.throw_on_failure)
    throw NumericalError("friction (pgs): did not converge: residual " + to_text(result.residual) + " > tol " +
                         to_text(options.tol) + " after " + std::to_string(sweep) + " sweeps (" + detail + ")");
  return result;
}

}  // namespace cdyn
