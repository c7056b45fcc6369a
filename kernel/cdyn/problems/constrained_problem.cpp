// problems/constrained_problem.cpp — load with lifting, full-field energy, violation, and the
// optional change of basis U_f = R U' (see problems/constrained_problem.hpp).
#include "cdyn/problems/constrained_problem.hpp"

#include <algorithm>

namespace cdyn {

const Eigen::VectorXd& ConstrainedProblem::full_load(double t) const {
  if (cached_full_load_.size() == 0 || (!load_is_constant && t != cached_t_)) {
    cached_full_load_ = L_full(t);
    cached_load_ = local(bc->restrict(Eigen::VectorXd(cached_full_load_ - A_full * UD)));
    cached_t_ = t;
  }
  return cached_full_load_;
}

const Eigen::VectorXd& ConstrainedProblem::load(double t) const {
  full_load(t);
  return cached_load_;
}

Eigen::VectorXd ConstrainedProblem::full(const Eigen::VectorXd& Uf) const {
  return R ? bc->extend(*R * Uf, UD) : bc->extend(Uf, UD);  // (no copy of Uf without R)
}

Eigen::VectorXd ConstrainedProblem::global(const Eigen::VectorXd& X) const {
  if (!R) return X;
  return *R * X;
}

Eigen::VectorXd ConstrainedProblem::local(const Eigen::VectorXd& X) const {
  if (!R) return X;
  return R->transpose() * X;
}

double ConstrainedProblem::potential_energy(const Eigen::VectorXd& Uf, double t) const {
  const Eigen::VectorXd U = full(Uf);
  return 0.5 * U.dot(A_full * U) - full_load(t).dot(U);
}

void ConstrainedProblem::bounds(double t, Eigen::VectorXd& lower_t, Eigen::VectorXd& upper_t) const {
  if (!moving_bounds) {
    lower_t = lower;
    upper_t = upper;
    return;
  }
  lower_t = lower;  // (the unconstrained entries keep their ±inf)
  upper_t = upper;
  moving_bounds(t, lower_t, upper_t);
}

double ConstrainedProblem::max_violation(const Eigen::VectorXd& Uf, double t) const {
  const Eigen::VectorXd* lo = &lower;
  const Eigen::VectorXd* up = &upper;
  Eigen::VectorXd lower_t, upper_t;
  if (moving_bounds) {
    bounds(t, lower_t, upper_t);
    lo = &lower_t, up = &upper_t;
  }
  double v = 0.0;
  for (int i : constrained) v = std::max({v, (*lo)[i] - Uf[i], Uf[i] - (*up)[i]});
  return v;
}

}  // namespace cdyn
