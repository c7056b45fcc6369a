// friction_pgs.cpp — projected Gauss–Seidel for the frictional step problem: the exact
// minimizer of (FQP) along one unknown at a time (qp/friction_solvers.hpp).
#include <algorithm>
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

// shrink(y, τ) = sign(y) max(|y| − τ, 0): the minimizer of ½(x − y)² + τ|x|.
double shrink(double y, double tau) { return y > tau ? y - tau : y < -tau ? y + tau : 0.0; }

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
  // role[i]: the contact whose tangential unknown i is, or −1
  std::vector<int> role(n, -1);
  for (int k = 0; k < m; ++k) {
    if (f.contacts[k].tangential.size() != 1)
      throw InputError("friction: pgs takes one tangential unknown per contact node (the plane)");
    role[f.contacts[k].tangential[0]] = k;
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
      const double z = X[i] - gradient(S, qp.r, X, i) / diag[i];  // the unconstrained minimizer along e_i
      const int k = role[i];
      if (k < 0) {
        X[i] = std::clamp(z, qp.lower[i], qp.upper[i]);
        continue;
      }
      const FrictionContact& c = f.contacts[k];
      const double s = c.coulomb ? c.mu * std::max(gradient(S, qp.r, X, c.normal), 0.0) : c.threshold;
      X[i] = f.reference[i] + shrink(z - f.reference[i], s / diag[i]);
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
    const int t = f.contacts[k].tangential[0];
    const double d = X[t] - f.reference[t];
    result.stick[k] = d == 0.0;
    if (d != 0.0) result.direction[t] = d > 0.0 ? 1.0 : -1.0;
  }
  result.qp.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result.converged && options.throw_on_failure)
    throw NumericalError("friction (pgs): did not converge: residual " + to_text(result.residual) + " > tol " +
                         to_text(options.tol) + " after " + std::to_string(sweep) + " sweeps (" + detail + ")");
  return result;
}

}  // namespace cdyn
