// nlopt.cpp — the step QP by NLopt's bound-constrained L-BFGS (or CCSAQ), matrix-free,
// with an active-set polishing; see qp/nlopt.hpp.
#include "cdyn/qp/nlopt.hpp"

#include <nlopt.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

struct Objective {
  const BoundQP* qp = nullptr;
  const QuadraticForm* form = nullptr;
  double tol = 0.0;
  int evaluations = 0;
  Eigen::VectorXd best;  // the first evaluated X whose KKT residual is ≤ tol
  bool found = false;
  nlopt_opt opt = nullptr;
};

// f(X) = ½ XᵀSX − rᵀX, ∇f = S X − r; stops NLopt once the KKT residual is below tol.
double objective(unsigned n, const double* x, double* grad, void* data) {
  auto& o = *static_cast<Objective*>(data);
  ++o.evaluations;
  const Eigen::Map<const Eigen::VectorXd> X(x, n);
  const Eigen::VectorXd g = o.form->gradient(X);
  if (grad) Eigen::Map<Eigen::VectorXd>(grad, n) = g;
  if (!o.found && kkt_residual(*o.qp, X, g, &o.form->diagonal()) <= o.tol) {
    o.found = true;
    o.best = X;
    nlopt_force_stop(o.opt);
  }
  return 0.5 * X.dot(g - o.qp->r);  // ½XᵀSX − rᵀX = ½ Xᵀ(g − r)
}

nlopt_algorithm algorithm(const std::string& name) {
  if (name == "LD_LBFGS") return NLOPT_LD_LBFGS;
  if (name == "LD_CCSAQ") return NLOPT_LD_CCSAQ;
  throw InputError("nlopt: algorithm '" + name + "' is not supported (LD_LBFGS or LD_CCSAQ)");
}

}  // namespace

NLoptSolver::NLoptSolver(const QPOptions& options) : options_(options) {
  if (options_.max_iterations == 0) options_.max_iterations = 20000;
  algorithm(options_.nlopt_algorithm);  // reject an unknown name at construction
}

QPResult NLoptSolver::solve(const BoundQP& qp, const QPResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  const bool new_matrices = checked_.check(qp, /*positive_definite=*/true, "nlopt");
  const int n = qp.size();
  form_.set(qp, !new_matrices);
  const Eigen::VectorXd& l = qp.lower;
  const Eigen::VectorXd& u = qp.upper;
  QPResult result;
  std::string detail;
  Eigen::VectorXd X = Eigen::VectorXd::Zero(n);
  if (warm_start && warm_start->X.size() == n) X = warm_start->X;
  for (int i = 0; i < n; ++i) X[i] = std::clamp(X[i], l[i], u[i]);

  int products = 0;  // products with S: the cost measure of a matrix-free method
  if (n > 0) {
    Objective data;
    data.qp = &qp;
    data.form = &form_;
    data.tol = options_.tol;
    nlopt_opt opt = nlopt_create(algorithm(options_.nlopt_algorithm), static_cast<unsigned>(n));
    data.opt = opt;
    nlopt_set_lower_bounds(opt, l.data());
    nlopt_set_upper_bounds(opt, u.data());
    nlopt_set_min_objective(opt, objective, &data);
    nlopt_set_ftol_rel(opt, 1e-16);
    nlopt_set_xtol_rel(opt, 1e-3 * options_.tol);
    nlopt_set_maxeval(opt, options_.max_iterations);
    nlopt_set_vector_storage(opt, 20);
    double fmin = 0.0;
    const nlopt_result status = nlopt_optimize(opt, X.data(), &fmin);
    nlopt_destroy(opt);
    products = data.evaluations;
    if (data.found) X = data.best;
    if (status < 0 && status != NLOPT_FORCED_STOP && status != NLOPT_ROUNDOFF_LIMITED)
      detail = std::string("NLopt: ") + nlopt_result_to_string(status);
    for (int i = 0; i < n; ++i) X[i] = std::clamp(X[i], l[i], u[i]);
  }
  result.X = X;
  finish_result(qp, form_, options_.tol, result);

  // Polishing: the active set by the PDAS rule, then S_II X_I = r_I − S_IA X_A by
  // Jacobi-preconditioned conjugate gradients (matrix-free).
  const Eigen::VectorXd& D = form_.diagonal();
  for (int round = 0; round < options_.nlopt_polish_rounds && !result.converged && n > 0; ++round) {
    std::vector<char> active(n, 0);
    for (int i = 0; i < n; ++i) {
      const double lam = result.reaction[i];
      if (l[i] == u[i] || (std::isfinite(l[i]) && lam + D[i] * (l[i] - X[i]) > 0)) {
        active[i] = 1;
        X[i] = l[i];
      } else if (std::isfinite(u[i]) && lam + D[i] * (u[i] - X[i]) < 0) {
        active[i] = 1;
        X[i] = u[i];
      }
    }
    auto restrict = [&](Eigen::VectorXd v) {
      for (int i = 0; i < n; ++i)
        if (active[i]) v[i] = 0.0;
      return v;
    };
    Eigen::VectorXd res = restrict(qp.r - form_.apply(X));  // r_I − (S X)_I
    ++products;
    Eigen::VectorXd z = res.cwiseQuotient(D), p = z;
    double rz = res.dot(z);
    const double scale = std::max(X.lpNorm<Eigen::Infinity>(), qp.r.cwiseQuotient(D).lpNorm<Eigen::Infinity>());
    for (int k = 0; k < 10 * n + 100 && products < 10 * options_.max_iterations; ++k) {
      if (z.lpNorm<Eigen::Infinity>() <= 1e-3 * options_.tol * scale) break;
      const Eigen::VectorXd Sp = restrict(form_.apply(p));
      ++products;
      const double alpha = rz / p.dot(Sp);
      X += alpha * p;
      res -= alpha * Sp;
      z = res.cwiseQuotient(D);
      const double rz_new = res.dot(z);
      p = z + (rz_new / rz) * p;
      rz = rz_new;
    }
    result.X = X;
    finish_result(qp, form_, options_.tol, result);
  }
  result.iterations = products;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_failure("nlopt", options_, result, detail);
  return result;
}

}  // namespace cdyn
