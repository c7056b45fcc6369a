// session.cpp — MPI and PETSc for a run on the PETSc back end; see session.hpp.
#include "session.hpp"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <string>
#include <thread>

#include "cdyn/base/error.hpp"
#include "distributed_qp.hpp"

namespace cdyn::petsc::session {

namespace {

bool started = false;
bool handler_pushed = false;
bool everyone_runs = false;  // every rank runs the program (no rank serves: subdomains)
// ranks_meet's own communicator: its barrier must not be matched with another
// collective call a waiting rank is in (measured: MPI_ERR_TRUNCATE, then a hang)
MPI_Comm meeting = MPI_COMM_NULL;

}  // namespace

void start() {
  if (started) return;
  if (PetscInitializeNoArguments() != 0) throw InputError("solver.backend: PETSc (and MPI) could not be initialized");
  // Errors come back as codes, turned into one-line exceptions (distributed_qp.cpp),
  // instead of PETSc's tracebacks on every rank.
  handler_pushed = !std::getenv("CDYN_PETSC_TRACE");
  if (handler_pushed) PetscPushErrorHandler(PetscIgnoreErrorHandler, nullptr);
  MPI_Comm_dup(PETSC_COMM_WORLD, &meeting);
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

bool ranks_meet(double seconds) {
  if (!started) return true;
  MPI_Request request;
  MPI_Ibarrier(meeting, &request);
  if (seconds < 0) {
    MPI_Wait(&request, MPI_STATUS_IGNORE);
    return true;
  }
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int done = 0;
  while (!done && std::chrono::steady_clock::now() < end) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return done != 0;  // (a request left pending: the caller ends the job)
}

void abort_all(int status) {
  MPI_Abort(MPI_COMM_WORLD, status);
  std::_Exit(status);  // (MPI_Abort does not return)
}

void reduce_over_ranks(double* x, int n, int op) {
  if (!started || n == 0) return;
  const MPI_Op how = op == 1 ? MPI_MAX : op == 2 ? MPI_MIN : MPI_SUM;
  MPI_Allreduce(MPI_IN_PLACE, x, n, MPI_DOUBLE, how, PETSC_COMM_WORLD);
}

std::vector<double> gather_on_first_rank(const std::vector<double>& x) {
  if (!started) return x;
  int n = static_cast<int>(x.size()), me = 0, p = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &me), MPI_Comm_size(PETSC_COMM_WORLD, &p);
  std::vector<int> counts(me == 0 ? p : 0), first(me == 0 ? p : 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, PETSC_COMM_WORLD);
  std::vector<double> all;
  if (me == 0) {
    for (int k = 1; k < p; ++k) first[k] = first[k - 1] + counts[k - 1];
    all.resize(first[p - 1] + counts[p - 1]);
  }
  MPI_Gatherv(x.data(), n, MPI_DOUBLE, all.data(), counts.data(), first.data(), MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  return all;
}

}  // namespace cdyn::petsc::session
