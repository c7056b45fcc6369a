// kkt.hpp — the one measure of how far X is from solving the step QP (qp/bound_qp.hpp),
// used by every solver (docs/qp.md):
//
//     F(X) = X − P(X − D⁻¹ λ),   λ = S X − r,   P the projection on the box,  D = diag(S),
//     kkt_residual(X) = ‖F(X)‖_∞ / max(‖X‖_∞, ‖D⁻¹ r‖_∞).
//
// F = 0 exactly at the solution; F measures infeasibility, stationarity and
// complementarity at once in units of X, and the quotient is invariant under scaling
// S, r or the bounds, so one `tol` means the same thing for every solver.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cdyn/qp/bound_qp.hpp"
#include "cdyn/qp/quadratic_form.hpp"

namespace cdyn {

// D = diag(S); in saddle form diag(A) + c Σ_k B_kj² / C_kk (C replaced by its diagonal:
// a scaling, not the exact diagonal, which would need C⁻¹).
Eigen::VectorXd scaling_diagonal(const BoundQP& qp);

// F_i = X_i − P_[l_i, u_i](X_i − λ_i / D_i), one entry of the natural residual below
// (inline: a solver's own pass over the unknowns computes it as kkt_maxima does).
inline double natural_residual_entry(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                                     const Eigen::VectorXd& D, int i) {
  const double step = X[i] - reaction[i] / D[i];
  return X[i] - std::clamp(step, qp.lower[i], qp.upper[i]);
}

// F(X) = X − P(X − D⁻¹ λ), the natural residual of the KKT conditions.
Eigen::VectorXd natural_residual(const BoundQP& qp, const Eigen::VectorXd& X,
                                 const Eigen::VectorXd& reaction, const Eigen::VectorXd& D);

// The common measure.  For the saddle form the first overload factorizes C each call;
// solvers use the second, with the gradient λ = S X − r they already have.
double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X);
double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                    const Eigen::VectorXd* D = nullptr);  // D = scaling_diagonal(qp) if already known

// The two maxima the measure is the ratio of, ‖F‖∞ (+∞ when an entry is not finite) and
// max(‖X‖∞, ‖D⁻¹r‖∞): for a caller that takes them over several processes' unknowns.
struct KKTMaxima {
  double F = 0.0, scale = 0.0;
  double residual() const { return std::isinf(F) || !(scale > 0) ? F : F / scale; }
};
KKTMaxima kkt_maxima(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                     const Eigen::VectorXd& D);

// The unknowns at a bound according to the rule of QPResult::active.
std::vector<int> active_set(const BoundQP& qp, const Eigen::VectorXd& X,
                            const Eigen::VectorXd& reaction, const Eigen::VectorXd& D);

// X_i set to the bound nearest to it, for every i of `active`: exactly at the bound it is
// held at, as an active-set solver's X_A = bound_A, where an interpolate of such
// solutions is there only to round-off.
void hold_at_bounds(const BoundQP& qp, const std::vector<int>& active, Eigen::VectorXd& X);
// Fills reaction, active, kkt_residual, converged of a result whose X is set, with the
// common measure.  `form` is the problem's QuadraticForm.
void finish_result(const BoundQP& qp, const QuadraticForm& form, double tol, QPResult& result);

// Throws NumericalError naming the solver, the residual and the iteration count when
// result.converged is false and options.throw_on_failure is set.
void report_failure(const std::string& solver, const QPOptions& options, const QPResult& result,
                    const std::string& detail = "");

}  // namespace cdyn
