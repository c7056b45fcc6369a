// projected_newton.cpp — Bertsekas (1982) projected Newton iteration on the step QP;
// see projected_newton.hpp.
#include "cdyn/qp/pdas/projected_newton.hpp"

#include <algorithm>

#include "cdyn/qp/kkt.hpp"

namespace cdyn {

ProjectedNewtonResult projected_newton(const BoundQP& qp, const QuadraticForm& form, ReducedSystem& system,
                                       Eigen::VectorXd X, int iterations, const QPOptions& options,
                                       const SolveTolerance& tolerance, PDASCounters& counters) {
  const int n = qp.size();
  const Eigen::VectorXd& l = qp.lower;
  const Eigen::VectorXd& u = qp.upper;
  const Eigen::VectorXd& D = form.diagonal();
  ProjectedNewtonResult out;
  out.iterations = iterations;
  for (int i = 0; i < n; ++i) X[i] = std::clamp(X[i], l[i], u[i]);
  const double eps_bar = std::max(X.lpNorm<Eigen::Infinity>(), qp.r.cwiseQuotient(D).lpNorm<Eigen::Infinity>());
  constexpr double sigma = 1e-4;
  HeldSet active(n);
  while (out.iterations < options.max_iterations) {
    ++out.iterations;
    ++counters.damped_iterations;
    const Eigen::VectorXd lam = form.gradient(X);
    if (kkt_residual(qp, X, lam, &D) <= options.tol) {
      out.X = X;
      return out;
    }
    // the ε-active set
    const double eps = std::min(eps_bar, natural_residual(qp, X, lam, D).lpNorm<Eigen::Infinity>());
    for (int i = 0; i < n; ++i)
      active[i] = l[i] == u[i] || (X[i] <= l[i] + eps && lam[i] > 0) || (X[i] >= u[i] - eps && lam[i] < 0);
    // the direction: Newton on the free unknowns, scaled gradient on the ε-active ones
    system.set_held(active);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = active[i] ? -lam[i] / D[i] : -lam[i];
    const Eigen::VectorXd p = system.solve_correction(b, tolerance(X, true));
    // Armijo along the projection arc X(t) = P(X + t p)
    double t = 1.0;
    bool accepted = false;
    Eigen::VectorXd Xt(n);
    while (t > 1e-20) {
      for (int i = 0; i < n; ++i) Xt[i] = std::clamp(X[i] + t * p[i], l[i], u[i]);
      const Eigen::VectorXd step = Xt - X;
      const double decrease = -(lam.dot(step) + 0.5 * step.dot(form.apply(step)));  // f(X) − f(X(t))
      double predicted = 0.0;
      for (int i = 0; i < n; ++i) predicted += active[i] ? lam[i] * (X[i] - Xt[i]) : -t * lam[i] * p[i];
      if (decrease >= sigma * predicted) {
        accepted = true;
        break;
      }
      t *= 0.5;
    }
    if (!accepted) {
      out.X = X;
      out.failure = "projected Newton line search stalled";
      return out;
    }
    X = Xt;
  }
  out.X = X;
  out.failure = "projected Newton after a cycling active set";
  return out;
}

}  // namespace cdyn
