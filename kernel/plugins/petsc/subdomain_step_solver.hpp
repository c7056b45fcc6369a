// kernel/plugins/petsc/subdomain_step_solver.hpp — the step QP assembled from the
// subdomains' shares, every rank holding its own (inside the plugin; the program makes
// it through qp/petsc/backend.hpp).
//
// In a run whose mesh is split into subdomains (mesh/sub_mesh.hpp), each rank builds the
// step QP of its own cells: S_r, r_r on its unknowns, which sit in the whole problem at
// global_r (problems/subdomain.hpp), with the whole problem's bounds there.  The step QP
// is their sum,
//     S = Σ_r P_rᵀ S_r P_r,   r = Σ_r P_rᵀ r_r,
// which the ranks add into one MPIAIJ matrix and one vector (PETSc's assembly sends each
// entry to the rank that owns its row), then solve with the distributed algorithms of
// distributed_qp.hpp.  Every rank calls solve() at once (no rank 0 commanding the others)
// and gets back the solution and the reaction λ = S X − r on its own unknowns, shared
// ones included; the KKT residual is the kernel's measure (qp/kkt.hpp) over all rows,
// its largest entry found by a reduction.
//
// Ownership: an unknown belongs to the lowest rank that holds it, and the ranks' owned
// unknowns are numbered one rank after the other (PETSc's contiguous rows), in the
// whole problem's order within each rank.  Found once, by a reduction over the whole
// problem's unknowns (one integer each: the first form, for the sizes that fit one
// process's memory anyway while the mesh is read by every rank).
#pragma once

#include <string>
#include <vector>

#include "cdyn/qp/step_solver.hpp"

namespace cdyn::petsc {

// name and preconditioner as for new_petsc_step_solver (petsc_step_solver.hpp); global:
// the whole problem's index of each unknown of this rank's QPs.  Explicit S only.
StepSolver* new_subdomain_step_solver(const std::vector<int>& global, const std::string& name,
                                      const QPOptions& options, const std::string& preconditioner);

}  // namespace cdyn::petsc
