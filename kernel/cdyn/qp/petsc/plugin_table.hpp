// qp/petsc/plugin_table.hpp — what the PETSc back end's plugin (libcdyn_petsc.so) gives
// the program that loads it (qp/petsc/backend.hpp): one table of functions.
//
// Why a plugin.  Debian's Ipopt is built on the sequential MUMPS, whose library defines
// a stand-in MPI (MPI_Comm_rank answering 0, ...) under MPI's own names.  In a process
// that has loaded it, PETSc's calls to MPI would reach those stand-ins unless PETSc is
// loaded apart: the plugin is opened with RTLD_LOCAL | RTLD_DEEPBIND, so that it and
// the libraries it brings (PETSc, OpenMPI, the parallel MUMPS) look up their symbols
// among themselves first.
#pragma once

#include <string>
#include <vector>

#include "cdyn/qp/step_solver.hpp"

namespace cdyn::petsc {

struct PluginTable {
  int version;  // kPluginVersion of the plugin's build
  void (*initialize)();
  int (*rank)();
  int (*size)();
  int (*serve)();
  void (*finalize)();
  // a new StepSolver (the caller owns it); InputError for an unknown name or preconditioner
  StepSolver* (*make_solver)(const std::string& name, const QPOptions& options, const std::string& preconditioner);
  // a new StepSolver of one subdomain's share, every rank solving at once (the caller owns it)
  StepSolver* (*make_subdomain_solver)(const std::vector<int>& global, const std::string& name,
                                       const QPOptions& options, const std::string& preconditioner);
  // collectives of a run whose every rank runs the program (the subdomains')
  void (*every_rank_runs)();                          // from now on: rank 0 commands no one
  void (*reduce_over_ranks)(double* x, int n, int op);  // op: Reduction, in place on every rank
  std::vector<double> (*gather_on_first_rank)(const std::vector<double>&);  // the ranks' in order, on rank 0
  // the rank of each vertex of a graph (offsets, neighbours), PT-Scotch's; collective
  std::vector<int> (*partition_graph)(const std::vector<int>&, const std::vector<int>&);
  bool (*ranks_meet)(double seconds);  // a barrier waited for at most `seconds` (< 0: forever)
  void (*abort_all)(int status);       // MPI_Abort
};

constexpr int kPluginVersion = 3;

}  // namespace cdyn::petsc

// The plugin's one exported symbol.
extern "C" const cdyn::petsc::PluginTable* cdyn_petsc_plugin();
