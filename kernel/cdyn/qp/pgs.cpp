// pgs.cpp — projected Gauss–Seidel / SOR (Cryer 1971); see qp/pgs.hpp.
#include "cdyn/qp/pgs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cdyn/base/error.hpp"

namespace cdyn {

PGSSolver::PGSSolver(const QPOptions& options) : options_(options) {
  if (options_.max_iterations == 0) options_.max_iterations = 100000;
  if (!(options_.pgs_omega > 0 && options_.pgs_omega < 2))
    throw InputError("pgs: omega = " + std::to_string(options_.pgs_omega) + " must lie in (0, 2)");
  if (options_.pgs_check_every < 1) options_.pgs_check_every = 1;
}

QPResult PGSSolver::solve(const BoundQP& qp, const QPResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  if (qp.saddle)
    throw InputError(
        "pgs: projected Gauss-Seidel needs the entries of S, but the problem is given in saddle form "
        "(S = A + c B^T C^-1 B with C^-1 dense); use solver pdas or ipopt");
  const bool new_matrices = checked_.check(qp, /*positive_definite=*/true, "pgs");
  const int n = qp.size();
  form_.set(qp, !new_matrices);
  const SparseMatrix& S = qp.S;  // symmetric: column i is row i
  const Eigen::VectorXd& l = qp.lower;
  const Eigen::VectorXd& u = qp.upper;
  const double omega = options_.pgs_omega;

  QPResult result;
  Eigen::VectorXd X = Eigen::VectorXd::Zero(n);
  if (warm_start && warm_start->X.size() == n) X = warm_start->X;
  for (int i = 0; i < n; ++i) X[i] = std::clamp(X[i], l[i], u[i]);

  const Eigen::VectorXd diag = S.diagonal();
  int sweep = 0;
  std::string detail;
  while (true) {
    if (sweep % options_.pgs_check_every == 0) {
      result.X = X;
      finish_result(qp, form_, options_.tol, result);
      if (result.converged) break;
      if (!std::isfinite(result.kkt_residual)) {
        detail = "the iterates are not finite";
        break;
      }
    }
    if (sweep >= options_.max_iterations) {
      detail = "maximum number of sweeps reached";
      break;
    }
    ++sweep;
    for (int i = 0; i < n; ++i) {
      double g = -qp.r[i];  // (S X − r)_i with the current X
      for (SparseMatrix::InnerIterator it(S, i); it; ++it) g += it.value() * X[it.row()];
      X[i] = std::clamp(X[i] - omega * g / diag[i], l[i], u[i]);
    }
  }
  result.iterations = sweep;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_failure("pgs", options_, result, detail);
  return result;
}

}  // namespace cdyn
