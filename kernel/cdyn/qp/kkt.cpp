// kkt.cpp — the common KKT measure of the step QP, and how a solver finishes a result.
#include "cdyn/qp/kkt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

Eigen::VectorXd scaling_diagonal(const BoundQP& qp) {
  if (!qp.saddle) return qp.S.diagonal();
  const SaddleForm& f = *qp.saddle;
  Eigen::VectorXd D = f.A.diagonal();
  const Eigen::VectorXd Cd = f.C.diagonal();
  for (int j = 0; j < f.B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(f.B, j); it; ++it) D[j] += f.c * it.value() * it.value() / Cd[it.row()];
  return D;
}

Eigen::VectorXd natural_residual(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                                 const Eigen::VectorXd& D) {
  const int n = qp.size();
  Eigen::VectorXd F(n);
  for (int i = 0; i < n; ++i) F[i] = natural_residual_entry(qp, X, reaction, D, i);
  return F;
}

// max |F_i| and the scale max(‖X‖∞, ‖r ./ D‖∞) in one pass shared among the threads (a
// maximum is exact in any order; a NaN anywhere makes the residual infinite).
KKTMaxima kkt_maxima(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                     const Eigen::VectorXd& D) {
  const int n = qp.size();
  double F = 0.0, scale = 0.0;
  bool finite = true;
#pragma omp parallel for schedule(static) reduction(max : F, scale) reduction(&& : finite) \
    if (6L * n >= kParallelWork)
  for (int i = 0; i < n; ++i) {
    const double f = std::abs(natural_residual_entry(qp, X, reaction, D, i));
    finite = finite && std::isfinite(f);
    F = std::max(F, f);
    scale = std::max({scale, std::abs(X[i]), std::abs(qp.r[i] / D[i])});
  }
  if (!finite) F = std::numeric_limits<double>::infinity();
  return {F, scale};
}

double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                    const Eigen::VectorXd* D_known) {
  if (qp.size() == 0) return 0.0;
  Eigen::VectorXd own;  // (the caller's D is read in place: no copy of n entries a call)
  if (!D_known) own = scaling_diagonal(qp);
  const KKTMaxima m = kkt_maxima(qp, X, reaction, D_known ? *D_known : own);
  return m.residual();
}

double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X) {
  QuadraticForm form;
  form.set(qp);
  return kkt_residual(qp, X, form.gradient(X));
}

std::vector<int> active_set(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                            const Eigen::VectorXd& D) {
  auto is_active = [&](int i) {
    const double l = qp.lower[i], u = qp.upper[i];
    return l == u || (std::isfinite(l) && reaction[i] > D[i] * (X[i] - l)) ||
           (std::isfinite(u) && reaction[i] < D[i] * (X[i] - u));
  };
  return indices_where(qp.size(), is_active);
}

void hold_at_bounds(const BoundQP& qp, const std::vector<int>& active, Eigen::VectorXd& X) {
  for (int i : active)
    X[i] = std::abs(X[i] - qp.lower[i]) <= std::abs(X[i] - qp.upper[i]) ? qp.lower[i] : qp.upper[i];
}

void finish_result(const BoundQP& qp, const QuadraticForm& form, double tol, QPResult& result) {
  result.reaction = form.gradient(result.X);
  const Eigen::VectorXd& D = form.diagonal();
  result.kkt_residual = kkt_residual(qp, result.X, result.reaction, &D);
  result.active = active_set(qp, result.X, result.reaction, D);
  result.converged = result.kkt_residual <= tol;
}

void report_failure(const std::string& solver, const QPOptions& options, const QPResult& result,
                    const std::string& detail) {
  if (result.converged || !options.throw_on_failure) return;
  throw NumericalError(solver + ": did not converge: KKT residual " + to_text(result.kkt_residual) + " > tol " +
                       to_text(options.tol) + " after " + std::to_string(result.iterations) + " iterations" +
                       (detail.empty() ? "" : " (" + detail + ")"));
}

}  // namespace cdyn
