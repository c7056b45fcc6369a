// kernel/plugins/petsc/petsc_step_solver.hpp — the step QP solvers of the PETSc back end, on rank 0
// (inside the plugin; the program makes them through qp/petsc/backend.hpp).
//
// They see what every step solver sees (qp/step_solver.hpp: S, r and the bounds) and
// solve it on all the ranks of the session (kernel/plugins/petsc/session.hpp), the rows of S spread
// over them (kernel/plugins/petsc/distributed_qp.hpp):
//   pdas       primal-dual active set (Hintermüller–Ito–Kunisch), CG on each reduced
//              system with Jacobi, GAMG or BoomerAMG (hypre);
//   tao_tron, tao_gpcg, tao_bqnls, tao_bncg   TAO's bound-constrained minimizers;
//   snesvi     SNES's reduced-space active set method for the KKT conditions;
// the last two families finish with active-set iterations to the common tol.  Every
// result is measured on rank 0 by the kernel's one KKT residual (qp/kkt.hpp) and a result
// above tol is a NumericalError, as for the serial solvers.  In saddle form (P1+/P1,
// P2/P1) pdas alone, each reduced saddle system by MUMPS's parallel LDLᵀ.
#pragma once

#include <string>

#include "cdyn/qp/step_solver.hpp"
#include "distributed_qp.hpp"

namespace cdyn::petsc {

// The algorithm and preconditioner of a solver's name and preconditioner (below);
// InputError naming `solver`, `pc` or `tol` for what the back end does not have.
struct SolverChoice {
  Algorithm algorithm = Algorithm::pdas;
  Preconditioner pc = Preconditioner::jacobi;
  bool pc_given = false;  // solver.pc set (refused in saddle form)
};
SolverChoice choose_solver(const std::string& name, const QPOptions& options, const std::string& preconditioner);

// name: pdas, tao_tron, tao_gpcg, tao_bqnls, tao_bncg or snesvi; preconditioner: gamg
// (pdas only), hypre or jacobi, empty for the default (jacobi); InputError otherwise.
// Starts the session if it is not yet.
StepSolver* new_petsc_step_solver(const std::string& name, const QPOptions& options, const std::string& preconditioner);

}  // namespace cdyn::petsc
