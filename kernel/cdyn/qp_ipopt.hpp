// qp_ipopt.hpp — the step QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp.hpp) solved by
// Ipopt, a primal-dual interior-point method (Wächter & Biegler, Math. Program. 106
// (2006) 25–57), through its C++ TNLP interface, MUMPS as the linear solver.
//
// Explicit S: variables X, no constraints, exact sparse Hessian S (lower triangle).
// Saddle form (S = A + c Bᵀ C⁻¹ B, seed eq. 11): variables (U, Z) with the linear
// equality constraints C Z − B U = 0 and the objective
//     ½ UᵀAU + (c/2) ZᵀCZ − rᵀU,
// equal to ½ UᵀSU − rᵀU on the constraint set (Z = C⁻¹BU); Hessian blockdiag(A, cC),
// Jacobian [−B, C], all sparse, nothing dense.
//
// Options (DESIGN.md §1, "Accuracy of each step solve"): bound_relax_factor = 0 so that
// the bounds hold exactly (Ipopt's default relaxes them by 1e-8 and biases the energy),
// Ipopt's tol = 1e-3 × QPOptions::tol, no output (print_level 0, sb = yes, no options
// file read), hessian/jacobian declared constant.  An interior point ends strictly
// inside the bounds at a distance of about μ/λ_i; the common KKT residual measures that
// distance, and the result is accepted only if it is ≤ tol (NumericalError otherwise).
// Warm start: the previous X as starting point (Ipopt moves it inside the bounds; an
// interior-point method gains little from it).  iterations: Ipopt's iterations
// (default max_iterations 3000).
#pragma once

#include "cdyn/qp.hpp"

namespace cdyn {

class IpoptSolver : public StepSolver {
 public:
  explicit IpoptSolver(const QPOptions& options = {});
  std::string name() const override { return "ipopt"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) override;

 private:
  QPOptions options_;
  SparseMatrix checked_S_;  // the last explicit S found positive definite
  QuadraticForm form_;
};

}  // namespace cdyn
