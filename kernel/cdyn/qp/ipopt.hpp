// ipopt.hpp — the step QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp/bound_qp.hpp) solved by
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
// Options (docs/qp.md §3.3; why the step solve must be accurate: docs/schemes.md,
// midpoint): bound_relax_factor = 0 so that the bounds hold exactly (Ipopt's default
// relaxes them by 1e-8 and biases the energy),
// tol = 1e-3 × QPOptions::tol, mu_min = 1e-10 × QPOptions::tol (the default floor 1e-11
// stops μ too early), adaptive μ, MUMPS, no output (print_level 0, sb = yes, no options
// file read), Hessian and Jacobian declared constant.
//
// Crossover.  An interior point ends strictly inside the bounds, at a distance ≈ μ/λ_i
// from an active bound; where λ_i is small (vertices at the edge of the contact zone)
// that distance, which the common KKT residual measures, stays far above tol: on the
// static obstacle Ipopt's own result has kkt_residual 1e-7 … 1e-12 however tight its
// tol (docs/qp.md).  As interior-point QP codes do, the result is then finished by a
// crossover: the active set Ipopt identified, and at most 3 steps of PDAS from it
// (exact sparse solves, qp/pdas/pdas.hpp).  QPOptions::ipopt_crossover = false turns it off
// (Ipopt's result then stands or falls alone); last() tells what Ipopt reached by itself.
// Still above tol: NumericalError.
//
// Warm start: the previous X as starting point (Ipopt moves it inside the bounds; an
// interior-point method gains little from it).  iterations: Ipopt's iterations plus the
// crossover's solves (default max_iterations 3000).
#pragma once

#include <memory>

#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class PDASSolver;

class IpoptSolver : public StepSolver {
 public:
  explicit IpoptSolver(const QPOptions& options = {});
  ~IpoptSolver() override;
  std::string name() const override { return "ipopt"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) override;
  void clear() override;  // the crossover's PDAS caches

  // What Ipopt itself achieved in the last solve, before the crossover.
  struct Statistics {
    int ipopt_iterations = 0;
    double ipopt_kkt_residual = 0.0;  // the common measure at Ipopt's own solution
    int crossover_solves = 0;         // PDAS solves of the crossover (0: not needed)
  };
  const Statistics& last() const { return last_; }

 private:
  QPOptions options_;
  std::unique_ptr<PDASSolver> crossover_;
  Statistics last_;
  CheckedMatrices checked_;  // input checks (and the PD check of S) once per distinct S
  QuadraticForm form_;
};

}  // namespace cdyn
