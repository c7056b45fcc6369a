// pgs.hpp — projected Gauss–Seidel with over-relaxation (projected SOR) for the step
// QP  min ½ XᵀSX − rᵀX,  lower ≤ X ≤ upper  (qp/bound_qp.hpp).
//
// Cryer, "The solution of a quadratic programming problem using systematic
// overrelaxation", SIAM J. Control 9 (1971) 385–392.  One sweep visits i = 0 … n−1:
//     X_i ← P_[lower_i, upper_i]( X_i − ω (S X − r)_i / S_ii ),
// each update using the X_j already updated in the sweep.  For S symmetric positive
// definite and 0 < ω < 2 it converges to the solution from any start (Cryer 1971;
// Mangasarian, J. Optim. Theory Appl. 22 (1977) 465–485), linearly, at the rate of SOR
// on S: about O(n_side) sweeps with the best ω, O(n_side²) with ω = 1 on a mesh.
//
// It needs the entries of S: the saddle form (S = A + c Bᵀ C⁻¹ B, C⁻¹ dense) is refused
// with an InputError — use pdas or ipopt for it.  The KKT residual (the common measure)
// is evaluated every QPOptions::pgs_check_every sweeps; iterations counts sweeps
// (default max_iterations 100000).  A new S is checked positive definite once (CHOLMOD).
#pragma once

#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class PGSSolver : public StepSolver {
 public:
  explicit PGSSolver(const QPOptions& options = {});
  std::string name() const override { return "pgs"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) override;

 private:
  QPOptions options_;
  CheckedMatrices checked_;  // input checks (and the PD check of S) once per distinct S
  QuadraticForm form_;
};

}  // namespace cdyn
