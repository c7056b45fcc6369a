// backend.cpp — opening the PETSc back end's plugin and calling it; see
// qp/petsc/backend.hpp.
#include "cdyn/qp/petsc/backend.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "cdyn/base/error.hpp"
#include "cdyn/base/plugin.hpp"
#include "cdyn/qp/petsc/plugin_table.hpp"

namespace cdyn::petsc {

namespace {

int env_int(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : 0;
}

// Where the plugin may be, in the order tried.
std::vector<std::filesystem::path> plugin_candidates() {
  std::vector<std::filesystem::path> out;
  if (const char* file = std::getenv("CDYN_PETSC_PLUGIN")) out.emplace_back(file);
  out.push_back(beside_installed_program("libcdyn_petsc.so"));
#ifdef CDYN_PETSC_PLUGIN_BUILD
  out.emplace_back(CDYN_PETSC_PLUGIN_BUILD);
#endif
  return out;
}

const PluginTable* opened = nullptr;
std::string refused;  // refuse()'s reason
bool all_ranks_run = false;  // every_rank_runs() was called

const PluginTable& plugin() {
  if (opened) return *opened;
  if (!refused.empty()) throw InputError("solver.backend", refused);
#ifndef CDYN_WITH_PETSC
  throw InputError("solver.backend", "this cdyn was built without PETSc (CDYN_WITH_PETSC=OFF)");
#else
  std::string tried;
  // RTLD_DEEPBIND: PETSc and MPI resolve among themselves first (plugin_table.hpp)
  opened = open_plugin<PluginTable>(plugin_candidates(), "cdyn_petsc_plugin", kPluginVersion,
                                    RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND, tried);
  if (opened) return *opened;
  throw InputError("solver.backend", "the PETSc plugin libcdyn_petsc.so was not found or not opened (" +
                                         (tried.empty() ? std::string("set CDYN_PETSC_PLUGIN to its path") : tried) +
                                         ")");
#endif
}

}  // namespace

bool launched_in_parallel() { return env_int("OMPI_COMM_WORLD_SIZE") > 1 || env_int("PMI_SIZE") > 1; }

bool built() {
#ifdef CDYN_WITH_PETSC
  return true;
#else
  return false;
#endif
}

void initialize() { plugin().initialize(); }
int rank() { return opened ? opened->rank() : 0; }
int size() { return opened ? opened->size() : 1; }
int serve() { return plugin().serve(); }

void refuse(const std::string& why) { refused = why; }

int end_process(int status) {
  if (!opened) return status;
  opened->finalize();
  std::cout.flush(), std::cerr.flush(), std::fflush(nullptr);
  std::_Exit(status);
}

std::unique_ptr<StepSolver> make_petsc_step_solver(const std::string& name, const QPOptions& options,
                                                   const std::string& preconditioner) {
  return std::unique_ptr<StepSolver>(plugin().make_solver(name, options, preconditioner));
}

void every_rank_runs() {
  plugin().every_rank_runs();
  all_ranks_run = true;
}

bool every_rank_running() { return all_ranks_run; }

void reduce_over_ranks(std::vector<double>& x, Reduction op) {
  if (opened) opened->reduce_over_ranks(x.data(), static_cast<int>(x.size()), static_cast<int>(op));
}

namespace {
double reduced(double x, Reduction op) {
  std::vector<double> v{x};
  reduce_over_ranks(v, op);
  return v[0];
}
}  // namespace

double sum_over_ranks(double x) { return reduced(x, Reduction::sum); }
double max_over_ranks(double x) { return reduced(x, Reduction::max); }

std::vector<double> gather_on_first_rank(const std::vector<double>& x) {
  return opened ? opened->gather_on_first_rank(x) : x;
}

bool ranks_meet(double seconds) { return opened ? opened->ranks_meet(seconds) : true; }

void abort_all(int status) {
  std::cout.flush(), std::cerr.flush(), std::fflush(nullptr);
  if (opened) opened->abort_all(status);
  std::_Exit(status);
}

std::vector<int> partition_graph(const std::vector<int>& offset, const std::vector<int>& neighbour) {
  if (!opened) return std::vector<int>(offset.size() - 1, 0);
  return opened->partition_graph(offset, neighbour);
}

std::unique_ptr<StepSolver> make_petsc_subdomain_solver(const std::vector<int>& global, const QPOptions& options,
                                                        const std::string& preconditioner, const std::string& name) {
  return std::unique_ptr<StepSolver>(plugin().make_subdomain_solver(global, name, options, preconditioner));
}

}  // namespace cdyn::petsc
