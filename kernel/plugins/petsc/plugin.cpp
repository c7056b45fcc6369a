// plugin.cpp — the PETSc back end's one exported symbol (qp/petsc/plugin_table.hpp).
#include "petsc_step_solver.hpp"
#include "subdomain_step_solver.hpp"
#include "cdyn/qp/petsc/plugin_table.hpp"
#include "graph_partition.hpp"
#include "session.hpp"

extern "C" __attribute__((visibility("default"))) const cdyn::petsc::PluginTable* cdyn_petsc_plugin() {
  namespace s = cdyn::petsc::session;
  static const cdyn::petsc::PluginTable table{cdyn::petsc::kPluginVersion, s::start, s::rank, s::size, s::serve,
                                              s::finish, cdyn::petsc::new_petsc_step_solver,
                                              cdyn::petsc::new_subdomain_step_solver, s::every_rank_runs,
                                              s::reduce_over_ranks, s::gather_on_first_rank,
                                              cdyn::petsc::partition_graph, s::ranks_meet, s::abort_all};
  return &table;
}
