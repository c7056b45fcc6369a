// qp/petsc/backend.hpp — the PETSc back end as the program sees it: the step QP solved
// on the ranks of `mpirun -n P cdyn run SCENE` (docs/distributed.md).
//
// The back end is a plugin, libcdyn_petsc.so (qp/petsc/plugin_table.hpp says why),
// opened on first use: from $CDYN_PETSC_PLUGIN if set, else next to an installed program
// (PREFIX/lib/cdyn/), else in the build tree.  Nothing here includes PETSc or MPI, and a
// serial run on the native back end never opens it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cdyn/qp/step_solver.hpp"

namespace cdyn::petsc {

// The environment of a process started by mpirun (OMPI_COMM_WORLD_SIZE, or PMI_SIZE for
// MPICH's launcher) with more than one process.  Read before MPI is initialized.
bool launched_in_parallel();

// Whether this build has the back end (CDYN_WITH_PETSC).
bool built();

// MPI and PETSc, once (InputError naming solver.backend when the plugin cannot be
// opened or PETSc cannot start).  rank() and size(): 0 and 1 before.
void initialize();
int rank();
int size();

// Ranks ≥ 1 of a parallel run: take part in rank 0's collective step solves until it
// says quit; returns the exit status.
int serve();

// The end of a process that may have opened the back end: rank 0 tells the others to
// quit, PETSc and MPI are finalized, and the process ends with `status` at once, after
// flushing the standard streams, without running the destructors of static objects —
// those of the C++ libraries PETSc brings (Trilinos's Teuchos) would flush an std::cout
// they see unconstructed under RTLD_DEEPBIND (plugin_table.hpp).  Without the back end
// opened, returns `status` (a normal exit).
int end_process(int status);

// Refuses the back end in this process from now on: InputError naming solver.backend,
// with `why`.  For the Python module, whose interpreter must end normally, which the
// process that opened the plugin cannot (end_process).
void refuse(const std::string& why);

// A step solver of the back end (qp/petsc/petsc_step_solver.hpp): name pdas,
// tao_tron, tao_gpcg, tao_bqnls, tao_bncg or snesvi; preconditioner gamg (pdas only),
// hypre or jacobi, empty for the default (jacobi).
std::unique_ptr<StepSolver> make_petsc_step_solver(const std::string& name, const QPOptions& options,
                                                   const std::string& preconditioner = "");

// A step solver for one subdomain's share of the step QP (mesh/sub_mesh.hpp), every rank
// of the session calling solve() at once with its own S_r, r_r and the whole problem's
// bounds on its unknowns, which sit at `global` in the whole problem
// (problems/subdomain.hpp): the QP solved is Σ_r P_rᵀ S_r P_r, Σ_r P_rᵀ r_r; each rank
// gets the solution and the reaction on its own unknowns.  `name` as for
// make_petsc_step_solver, explicit S only (kernel/plugins/petsc/subdomain_step_solver.hpp).
// Collective from construction on.
// `global` may leave gaps (labels no rank holds).  Given to a scheme, the solver learns
// which of these unknowns its QPs keep (StepSolver::set_unknowns) and condenses the
// bubbles only (StepSolver::solves_a_share).
std::unique_ptr<StepSolver> make_petsc_subdomain_solver(const std::vector<int>& global, const QPOptions& options,
                                                        const std::string& preconditioner = "",
                                                        const std::string& name = "pdas");

// A run whose ranks all run the program (the subdomains'): from now on none waits for
// rank 0's commands (serve()), and rank 0 sends none at the end.  Before anything
// collective.
void every_rank_runs();
// Whether every_rank_runs() was called in this process.
bool every_rank_running();
// Its collectives, each called by every rank; without the back end opened, x itself.
enum class Reduction { sum = 0, max = 1, min = 2 };
// x reduced over the ranks in place, on every rank.
void reduce_over_ranks(std::vector<double>& x, Reduction op);
double sum_over_ranks(double x);
double max_over_ranks(double x);
// Every rank's x, rank after rank, on rank 0 (empty on the others).
std::vector<double> gather_on_first_rank(const std::vector<double>& x);
// Whether every rank reaches this call within `seconds` (forever when < 0): the end of a
// run on subdomains, where a rank that failed alone (the others waiting for it in a
// collective call) gives up after a while; true without the back end opened.
bool ranks_meet(double seconds);
// Ends every process of the job with `status` (MPI_Abort); std::_Exit without the back end.
[[noreturn]] void abort_all(int status);
// The rank of each vertex of a graph given whole on every rank (the neighbours of v:
// neighbour[offset[v]] … neighbour[offset[v + 1] − 1]), by PT-Scotch: parts of about
// equal size with few cut edges, the same on every rank (all 0 without the back end).
std::vector<int> partition_graph(const std::vector<int>& offset, const std::vector<int>& neighbour);

}  // namespace cdyn::petsc
