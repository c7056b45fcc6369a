// petsc_step_solver.cpp — rank 0's side of the distributed step solvers; see
// kernel/plugins/petsc/petsc_step_solver.hpp.
#include "petsc_step_solver.hpp"

#include <chrono>
#include <cmath>
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
  PetscStepSolver(std::string name, Algorithm algorithm, Preconditioner pc, bool pc_given, const QPOptions& options)
      : name_(std::move(name)), algorithm_(algorithm), pc_(pc), pc_given_(pc_given), options_(options) {}

  // A solver made later at this one's address must not take the distributed S for its own.
  ~PetscStepSolver() override {
    if (matrix_owner().solver == this) matrix_owner() = {};
  }

  std::string name() const override { return "petsc " + name_; }

  QPResult solve(const BoundQP& qp, const QPResult* warm_start) override {
    const auto start = std::chrono::steady_clock::now();
    if (qp.saddle) refuse_in_saddle_form();
    const bool new_matrix = checked_.check(qp, /*positive_definite=*/false, name());
    if (new_matrix) ++version_;
    form_.set(qp, !new_matrix);
    const BoundQP& sent = qp.saddle ? extended(qp, new_matrix) : qp;
    // S is sent when this solver's S is new, or another solver's is the one distributed
    MatrixOwner& owner = matrix_owner();
    DistributedQP& q = the_distributed_qp();
    SolveSettings settings;
    settings.n = sent.size();
    settings.saddle_rows = sent.size() - qp.size();
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
      const QPResult* warm = !settings.warm ? nullptr : qp.saddle ? extended(*warm_start) : warm_start;
      q.receive(settings, &sent, warm, &saddle_D_);
      result.iterations = solve_collectively(q, settings);
    } catch (const NumericalError& e) {
      failure = e.what();
    }
    result.X = q.gather_solution().head(qp.size());
    if (!failure.empty()) throw NumericalError(name() + ": " + failure);
    finish_result(qp, form_, options_.tol, result);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_failure(name(), options_, result, "");
    return result;
  }

  // Saddle form: pdas with a direct solve of the reduced saddle system (distributed_pdas.cpp).
  void refuse_in_saddle_form() const {
    if (algorithm_ != Algorithm::pdas)
      throw InputError("solver", name_ + " needs the step matrix S explicitly; in saddle form (H^h continuous: "
                                         "P1+/P1, P2/P1) the petsc back end solves by pdas");
    if (pc_given_)
      throw InputError("pc", "the petsc pdas solves the saddle form (H^h continuous: P1+/P1, P2/P1) by MUMPS's "
                             "factorization, which takes no preconditioner");
  }

  // The saddle-form qp as the distributed pdas takes it: K [X; Z] with Z unbounded
  // (base/sparse.hpp), and the rule's scaling D; K and D made again with the matrices.
  const BoundQP& extended(const BoundQP& qp, bool new_matrix) {
    const int n = qp.size(), m = static_cast<int>(qp.saddle->C.rows());
    if (new_matrix || saddle_qp_.S.rows() != n + m) {
      saddle_qp_.S = symmetric_saddle_matrix(*qp.saddle);
      saddle_D_.resize(n + m);
      saddle_D_ << form_.diagonal(), Eigen::VectorXd::Ones(m);
    }
    saddle_qp_.r.resize(n + m), saddle_qp_.lower.resize(n + m), saddle_qp_.upper.resize(n + m);
    saddle_qp_.r << qp.r, Eigen::VectorXd::Zero(m);
    saddle_qp_.lower << qp.lower, Eigen::VectorXd::Constant(m, -INFINITY);
    saddle_qp_.upper << qp.upper, Eigen::VectorXd::Constant(m, INFINITY);
    return saddle_qp_;
  }
  // A warm start extended by Z = 0 and its reaction by 0 (the rule reads X's rows only).
  const QPResult* extended(const QPResult& warm) {
    const int n = static_cast<int>(warm.X.size()), m = static_cast<int>(saddle_qp_.S.rows()) - n;
    saddle_warm_.X.resize(n + m), saddle_warm_.reaction.resize(n + m);
    saddle_warm_.X << warm.X, Eigen::VectorXd::Zero(m);
    saddle_warm_.reaction << warm.reaction, Eigen::VectorXd::Zero(m);
    return &saddle_warm_;
  }

  void clear() override {
    if (session::size() > 1) send(Command::clear);
    the_distributed_qp().clear();
  }

 private:
  std::string name_;
  Algorithm algorithm_;
  Preconditioner pc_;
  bool pc_given_;  // solver.pc set (refused in saddle form)
  QPOptions options_;
  CheckedMatrices checked_;  // input checks once per distinct S
  BoundQP saddle_qp_;        // in saddle form, the extended problem sent
  QPResult saddle_warm_;
  Eigen::VectorXd saddle_D_;
  QuadraticForm form_;
  unsigned long version_ = 0;  // counts this solver's distinct S
};

}  // namespace

SolverChoice choose_solver(const std::string& name, const QPOptions& options, const std::string& preconditioner) {
  if (!(options.tol > 0)) throw InputError("tol", "must be a positive number");
  SolverChoice choice;
  choice.algorithm = lookup(kAlgorithms, name, "solver", "a step solver");
  // The default, Jacobi: the step matrix is well conditioned when dt ∝ h (CG needs a
  // few dozen iterations), and an algebraic multigrid's set-up at every change of the
  // active set costs far more than it saves (measured, docs/distributed.md: GAMG 3.6 s
  // a step where Jacobi takes 0.09 s on the 16³ cube).
  choice.pc = lookup(kPreconditioners, preconditioner.empty() ? "jacobi" : preconditioner, "pc", "a preconditioner");
  choice.pc_given = !preconditioner.empty();
  // TAO's and SNESVI's Krylov solves see a matrix of another size at every iteration,
  // which PETSc 3.18's GAMG does not take (its coarse solver keeps the first sizes)
  if (choice.pc == Preconditioner::gamg && choice.algorithm != Algorithm::pdas)
    throw InputError("pc", "gamg cannot precondition " + name +
                               ", whose systems change size with the free set (use hypre or jacobi)");
  return choice;
}

StepSolver* new_petsc_step_solver(const std::string& name, const QPOptions& options, const std::string& preconditioner) {
  const SolverChoice choice = choose_solver(name, options, preconditioner);
  session::start();
  return new PetscStepSolver(name, choice.algorithm, choice.pc, choice.pc_given, options);
}

}  // namespace cdyn::petsc
