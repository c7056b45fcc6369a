// petsc_step_solver.cpp — rank 0's side of the distributed step solvers; see
// kernel/plugins/petsc/petsc_step_solver.hpp.
#include "petsc_step_solver.hpp"

#include <chrono>
#include <utility>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "distributed_qp.hpp"
#include "session.hpp"

namespace cdyn::petsc {

namespace {

const std::vector<std::pair<std::string, Algorithm>> kAlgorithms = {
    {"pdas", Algorithm::pdas},          {"tao_tron", Algorithm::tao_tron}, {"tao_gpcg", Algorithm::tao_gpcg},
    {"tao_bqnls", Algorithm::tao_bqnls}, {"tao_bncg", Algorithm::tao_bncg}, {"snesvi", Algorithm::snesvi}};
const std::vector<std::pair<std::string, Preconditioner>> kPreconditioners = {
    {"gamg", Preconditioner::gamg}, {"hypre", Preconditioner::hypre}, {"jacobi", Preconditioner::jacobi}};

// The entry of a name table, or InputError naming the parameter and the table's names.
template <class T>
T lookup(const std::vector<std::pair<std::string, T>>& table, const std::string& name, const char* parameter,
         const char* what) {
  std::string known;
  for (const auto& [key, value] : table) {
    if (key == name) return value;
    known += (known.empty() ? "" : ", ") + key;
  }
  throw InputError(parameter, "'" + name + "' is not " + what + " of the petsc back end (available: " + known + ")");
}

class PetscStepSolver : public StepSolver {
 public:
  PetscStepSolver(std::string name, Algorithm algorithm, Preconditioner pc, const QPOptions& options)
      : name_(std::move(name)), algorithm_(algorithm), pc_(pc), options_(options) {}

  std::string name() const override { return "petsc " + name_; }

  QPResult solve(const BoundQP& qp, const QPResult* warm_start) override {
    const auto start = std::chrono::steady_clock::now();
    if (qp.saddle)
      throw InputError("solver.backend", "petsc needs the step matrix S explicitly; this pair's step is in saddle form "
                                         "(H^h continuous: P1+/P1, P2/P1), use solver.backend = \"native\"");
    const bool new_matrix = checked_.check(qp, /*positive_definite=*/false, name());
    if (new_matrix) ++version_;
    form_.set(qp, !new_matrix);
    // S is sent when this solver's S is new, or another solver's is the one distributed
    MatrixOwner& owner = matrix_owner();
    DistributedQP& q = the_distributed_qp();
    SolveSettings settings;
    settings.n = qp.size();
    settings.matrix_changed = !q.has_matrix() || owner.solver != this || owner.version != version_;
    settings.warm = warm_start && warm_start->X.size() == qp.size() && warm_start->reaction.size() == qp.size();
    settings.algorithm = algorithm_;
    settings.pc = pc_;
    settings.tol = options_.tol;
    settings.max_iterations = options_.max_iterations;
    owner = {this, version_};

    if (session::size() > 1) send(Command::solve);
    QPResult result;
    std::string failure;
    try {
      q.receive(settings, &qp, settings.warm ? warm_start : nullptr);
      result.iterations = solve_collectively(q, settings);
    } catch (const NumericalError& e) {
      failure = e.what();
    }
    result.X = q.gather_solution();
    if (!failure.empty()) throw NumericalError(name() + ": " + failure);
    finish_result(qp, form_, options_.tol, result);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_failure(name(), options_, result, "");
    return result;
  }

  void clear() override {
    if (session::size() > 1) send(Command::clear);
    the_distributed_qp().clear();
  }

 private:
  std::string name_;
  Algorithm algorithm_;
  Preconditioner pc_;
  QPOptions options_;
  CheckedMatrices checked_;  // input checks once per distinct S
  QuadraticForm form_;
  unsigned long version_ = 0;  // counts this solver's distinct S
};

}  // namespace

StepSolver* new_petsc_step_solver(const std::string& name, const QPOptions& options, const std::string& preconditioner) {
  if (!(options.tol > 0)) throw InputError("tol", "must be a positive number");
  const Algorithm algorithm = lookup(kAlgorithms, name, "solver", "a step solver");
  // The default, Jacobi: the step matrix is well conditioned when dt ∝ h (CG needs a
  // few dozen iterations), and an algebraic multigrid's set-up at every change of the
  // active set costs far more than it saves (measured, docs/distributed.md: GAMG 3.6 s
  // a step where Jacobi takes 0.09 s on the 16³ cube).
  const Preconditioner pc =
      lookup(kPreconditioners, preconditioner.empty() ? "jacobi" : preconditioner, "pc", "a preconditioner");
  // TAO's and SNESVI's Krylov solves see a matrix of another size at every iteration,
  // which PETSc 3.18's GAMG does not take (its coarse solver keeps the first sizes)
  if (pc == Preconditioner::gamg && algorithm != Algorithm::pdas)
    throw InputError("pc", "gamg cannot precondition " + name +
                               ", whose systems change size with the free set (use hypre or jacobi)");
  session::start();
  return new PetscStepSolver(name, algorithm, pc, options);
}

}  // namespace cdyn::petsc
