// reference_pdas.hpp — the primal-dual active set method in its textbook form, as a test
// oracle for the production solver (pdas.hpp).
//
// Hintermüller, Ito & Kunisch, SIAM J. Optim. 13 (2002) 865–888 (with the diagonal
// scaling D = diag S in place of their constant c, as pdas.hpp):
//     A_l = {i : λ_i + D_i(lower_i − X_i) > 0},   A_u = {i : λ_i + D_i(upper_i − X_i) < 0},
//     X = lower on A_l,  X = upper on A_u,  S_II X_I = r_I − S_IA X_A on the rest I,
//     λ = S X − r,
// until the active set repeats.  Every iterate extracts the free block and factorizes it
// from scratch with other code than the production solver's: S_II by Eigen's
// SimplicialLDLT (explicit S), and in saddle form the reduced saddle matrix
//     [[A_II, c B_Iᵀ], [B_I, −C]] [X_I; Z] = [r_I − A_IA X_A; −B_A X_A]
// by Eigen's SparseLU.  No CG, no kept factor, no row updates, no refinement, no
// cycling guard: if the set does not repeat within max_iterations (default 100), it
// fails (NumericalError, or converged = false).  A warm start gives only the first
// active set (each previous active unknown at its nearer bound).  Slow by design:
// meant for tests, not registered in make_step_solver().
#pragma once

#include "cdyn/qp/step_solver.hpp"

namespace cdyn {

class ReferencePDASSolver : public StepSolver {
 public:
  explicit ReferencePDASSolver(const QPOptions& options = {});
  std::string name() const override { return "reference_pdas"; }
  QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) override;

 private:
  QPOptions options_;
};

}  // namespace cdyn
