// session.cpp — MPI and PETSc for a run on the PETSc back end; see session.hpp.
#include "session.hpp"

#include <csignal>
#include <cstdlib>
#include <string>

#include "cdyn/base/error.hpp"
#include "distributed_qp.hpp"

namespace cdyn::petsc::session {

namespace {

bool started = false;
bool handler_pushed = false;
bool everyone_runs = false;  // every rank runs the program (no rank serves: subdomains)

}  // namespace

void start() {
  if (started) return;
  if (PetscInitializeNoArguments() != 0) throw InputError("solver.backend: PETSc (and MPI) could not be initialized");
  // Errors come back as codes, turned into one-line exceptions (distributed_qp.cpp),
  // instead of PETSc's tracebacks on every rank.
  handler_pushed = !std::getenv("CDYN_PETSC_TRACE");
  if (handler_pushed) PetscPushErrorHandler(PetscIgnoreErrorHandler, nullptr);
  started = true;
}

int rank() {
  int r = 0;
  if (started) MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

int size() {
  int s = 1;
  if (started) MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

int serve() {
  std::signal(SIGINT, SIG_IGN);
  DistributedQP& q = petsc::the_distributed_qp();
  for (;;) {
    switch (receive()) {
      case Command::quit:
        return 0;
      case Command::clear:
        q.clear();
        break;
      case Command::solve:
        try {
          SolveSettings settings;
          q.receive(settings, nullptr, nullptr);
          solve_collectively(q, settings);
        } catch (const std::exception&) {
          // the failures of a collective solve are the same on every rank: rank 0 reports
          // it and goes on (or stops and says quit)
        }
        q.gather_solution();  // as rank 0 does, failed or not
        break;
    }
  }
}

void finish() {
  if (!started) return;
  if (rank() == 0 && size() > 1 && !everyone_runs) send(Command::quit);
  the_distributed_qp().clear();
  if (handler_pushed) PetscPopErrorHandler();  // (freed, as everything else, before the finalization)
  PetscFinalize();
  started = false;
}

void every_rank_runs() { everyone_runs = true; }

double sum_over_ranks(double x) {
  if (started) MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return x;
}

}  // namespace cdyn::petsc::session
