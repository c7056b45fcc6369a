// kernel/plugins/petsc/session.hpp — the MPI and PETSc session of a run on the PETSc back end, and
// the roles of its processes (inside the plugin; the program reaches these through
// qp/petsc/backend.hpp).
//
// Under `mpirun -n P cdyn run SCENE` one scene is integrated by rank 0, as a serial run
// would; ranks 1 … P−1 hold their share of the rows of each step QP (qp/bound_qp.hpp) and
// take part in its solve, the stage whose cost grows fastest with the mesh
// (docs/distributed.md).  Before every collective operation rank 0 sends the others a
// command: solve a step QP, forget the distributed matrix, or quit.  On one process
// (`cdyn run` alone, or mpirun -n 1) the same code runs with nobody to command.
#pragma once

#include <vector>

namespace cdyn::petsc::session {

// Initializes MPI and PETSc once (later calls do nothing); PETSc's own options still come
// from the environment variable PETSC_OPTIONS.  InputError if PETSc cannot start.
void start();
int rank();  // 0 before start()
int size();  // 1 before start()
// Ranks ≥ 1: take part in every collective solve rank 0 starts, until it says quit.
// SIGINT is ignored here: Ctrl-C reaches rank 0, whose run stops cleanly and then says
// quit.  Returns the process's exit status (0).
int serve();
// Rank 0 tells the others to quit; then PETSc and MPI are finalized (if started).
void finish();
// x[0..n) reduced over the ranks in place, on every rank: op 0 the sum, 1 the largest, 2
// the smallest (backend.hpp's Reduction); collective, x itself before start().
void reduce_over_ranks(double* x, int n, int op);
// Every rank's x, rank after rank, on rank 0 (empty elsewhere); collective, x before start().
std::vector<double> gather_on_first_rank(const std::vector<double>& x);
// Whether every rank reaches this call within `seconds` (forever when < 0): a barrier
// that a rank may give up waiting for (collective; true before start()).
bool ranks_meet(double seconds);
// Ends every process of the job with `status` (MPI_Abort).
[[noreturn]] void abort_all(int status);
// Every rank runs the program, none serves (the subdomains' solves,
// subdomain_step_solver.hpp): finish() then sends no quit.
void every_rank_runs();

}  // namespace cdyn::petsc::session
