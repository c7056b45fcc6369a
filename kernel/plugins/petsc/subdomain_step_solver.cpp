// subdomain_step_solver.cpp — the step QP summed from the subdomains' shares and solved
// on every rank at once; see kernel/plugins/petsc/subdomain_step_solver.hpp.
#include "subdomain_step_solver.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <string>
#include <memory>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "distributed_qp.hpp"
#include "petsc_step_solver.hpp"
#include "session.hpp"

namespace cdyn::petsc {

namespace {

MPI_Comm world() { return PETSC_COMM_WORLD; }

// True on every rank when `changed` is on any.
bool on_any_rank(bool changed) { return global_max(changed ? 1.0 : 0.0) > 0; }

class SubdomainStepSolver : public StepSolver {
 public:
  SubdomainStepSolver(const std::vector<int>& global, const std::string& name, const SolverChoice& choice,
                      const QPOptions& options)
      : labels_(global), global_(global), options_(options), name_(name), choice_(choice) {
    number_unknowns();
  }
  ~SubdomainStepSolver() override { forget_layout(); }
  std::string name() const override { return "petsc " + name_ + " (subdomains)"; }
  bool solves_a_share() const override { return true; }
  // The same labels, another QP (collective: every rank makes it at once).
  std::unique_ptr<StepSolver> make_companion(const QPOptions& options) const override {
    return std::make_unique<SubdomainStepSolver>(labels_, name_, choice_, options);
  }

  // The QPs' unknowns are now these of the labelled ones (a scheme's condensation keeps
  // some): numbered again, the matrix assembled again at the next solve.  Collective.
  void set_unknowns(const std::vector<int>& free_unknowns) override {
    global_.clear();
    for (int i : free_unknowns) global_.push_back(labels_.at(i));
    forget_layout();
    number_unknowns();
  }

  int count_in_whole(const std::vector<int>& unknowns) const override {
    int mine = 0;
    for (int i : unknowns) mine += owns(i);
    MPI_Allreduce(MPI_IN_PLACE, &mine, 1, MPI_INT, MPI_SUM, world());
    return mine;
  }

  bool owns(int unknown) const override {
    const PetscInt i = petsc_of_.at(unknown);
    return i >= q_.first && i < q_.last;
  }

  // Σ_r P_rᵀ x_r at this rank's unknowns, as r is summed (assemble_vectors).
  Eigen::VectorXd summed(const Eigen::VectorXd& x) const override {
    if (x.size() != static_cast<Eigen::Index>(petsc_of_.size()))
      throw InputError(name() + ": a vector of " + std::to_string(x.size()) + " entries to sum, the subdomain has " +
                       std::to_string(petsc_of_.size()) + " unknowns");
    Owned<Vec, VecDestroy> sum;
    check(VecCreateMPI(world(), q_.last - q_.first, n_, sum.out()), "VecCreateMPI");
    check(VecSetValues(sum, static_cast<PetscInt>(x.size()), petsc_of_.data(), x.data(), ADD_VALUES), "VecSetValues");
    check(VecAssemblyBegin(sum), "VecAssemblyBegin");
    check(VecAssemblyEnd(sum), "VecAssemblyEnd");
    make_scatter(sum);
    return values_at(sum);
  }

  double total(double x) const override {
    MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_SUM, world());
    return x;
  }
  double largest(double x) const override { return global_max(x); }

  QPResult solve(const BoundQP& qp, const QPResult* warm_start) override {
    const auto start = std::chrono::steady_clock::now();
    // The input checks, agreed on by every rank before anything collective: a rank that
    // threw alone would leave the others waiting in the next reduction.
    std::string bad;
    bool changed = false;
    try {
      if (qp.saddle) throw InputError("solver", name() + " takes an explicit step matrix (not the saddle form)");
      if (qp.size() != static_cast<int>(global_.size()))
        throw InputError(name() + ": the QP has " + std::to_string(qp.size()) + " unknowns, the subdomain " +
                         std::to_string(global_.size()));
      changed = checked_.check(qp, /*positive_definite=*/false, name());
    } catch (const InputError& e) {
      bad = e.what();
    }
    if (on_any_rank(!bad.empty()))
      throw InputError(bad.empty() ? name() + ": another rank's share of the QP is not valid" : bad);
    // S assembled again when any rank's share changed
    if (on_any_rank(changed || !q_.S)) assemble_matrix(qp.S);
    assemble_vectors(qp, warm_start);

    SolveSettings settings;
    settings.n = n_;
    settings.warm = warm_start && warm_start->X.size() == qp.size() && warm_start->reaction.size() == qp.size();
    settings.algorithm = choice_.algorithm;
    settings.pc = choice_.pc;
    settings.tol = options_.tol;
    settings.max_iterations = options_.max_iterations;
    QPResult result;
    last_X_.resize(0);  // (q_.X is the iterate from here on)
    try {
      result.iterations = solve_collectively(q_, settings);
    } catch (const NumericalError& e) {  // (the same on every rank: reasons and tests are global)
      throw NumericalError(name() + ": " + e.what());
    }
    check(MatMult(q_.S, q_.X, q_.reaction), "MatMult");  // λ = S X − r
    check(VecAXPY(q_.reaction, -1.0, q_.r), "VecAXPY");
    result.X = values_at(q_.X);
    result.reaction = values_at(q_.reaction);
    last_X_ = result.X, last_reaction_ = result.reaction;
    const Eigen::VectorXd D = values_at(diagonal_);
    result.kkt_residual = kkt_over_ranks(qp, result, D);
    result.active = active_set(qp, result.X, result.reaction, D);
    result.converged = result.kkt_residual <= options_.tol;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_failure(name(), options_, result, "");
    return result;
  }

 private:
  // Owners (the lowest rank holding each unknown) and PETSc's numbering, in the labels'
  // order (labels no rank holds, as a whole problem's condensed bubbles, are skipped).
  void number_unknowns() {
    int me = 0, p = 1;
    MPI_Comm_rank(world(), &me), MPI_Comm_size(world(), &p);
    int n = global_.empty() ? 0 : *std::max_element(global_.begin(), global_.end()) + 1;
    MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_INT, MPI_MAX, world());
    std::vector<int> owner(n, INT_MAX);
    for (int g : global_) owner[g] = me;
    MPI_Allreduce(MPI_IN_PLACE, owner.data(), n, MPI_INT, MPI_MIN, world());
    std::vector<PetscInt> first(p + 1, 0), petsc(n, -1);
    for (int g = 0; g < n; ++g)
      if (owner[g] != INT_MAX) ++first[owner[g] + 1];
    for (int k = 0; k < p; ++k) first[k + 1] += first[k];
    std::vector<PetscInt> next(first.begin(), first.end() - 1);
    for (int g = 0; g < n; ++g)
      if (owner[g] != INT_MAX) petsc[g] = next[owner[g]]++;
    n_ = static_cast<int>(first[p]);
    q_.n = n_;
    q_.first = first[me], q_.last = first[me + 1];
    petsc_of_.resize(global_.size());
    for (std::size_t i = 0; i < global_.size(); ++i) petsc_of_[i] = petsc[global_[i]];
  }

  // S = Σ_r P_rᵀ S_r P_r: each rank adds its entries, PETSc sends them to their rows' owners.
  void assemble_matrix(const SparseMatrix& S_r) {
    if (q_.S) MatDestroy(&q_.S);
    int widest = 0;  // preallocation: a row of the sum has at most the ranks' widest row, twice
    for (int j = 0; j < S_r.outerSize(); ++j) widest = std::max(widest, static_cast<int>(S_r.innerVector(j).nonZeros()));
    MPI_Allreduce(MPI_IN_PLACE, &widest, 1, MPI_INT, MPI_MAX, world());
    const PetscInt local = q_.last - q_.first;
    check(MatCreateAIJ(world(), local, local, n_, n_, 2 * widest, nullptr, 2 * widest, nullptr, &q_.S), "MatCreateAIJ");
    check(MatSetOption(q_.S, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
    std::vector<PetscInt> rows;
    std::vector<PetscScalar> values;
    for (int j = 0; j < S_r.outerSize(); ++j) {  // S_r symmetric: column j is row j
      rows.clear(), values.clear();
      for (SparseMatrix::InnerIterator it(S_r, j); it; ++it)
        rows.push_back(petsc_of_[it.row()]), values.push_back(it.value());
      const PetscInt row = petsc_of_[j];
      check(MatSetValues(q_.S, 1, &row, static_cast<PetscInt>(rows.size()), rows.data(), values.data(), ADD_VALUES),
            "MatSetValues");
    }
    check(MatAssemblyBegin(q_.S, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(q_.S, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    for (Vec* v : {&q_.r, &q_.lower, &q_.upper, &q_.X, &q_.reaction, &diagonal_})
      if (!*v) check(MatCreateVecs(q_.S, v, nullptr), "MatCreateVecs");
    check(MatGetDiagonal(q_.S, diagonal_), "MatGetDiagonal");
    make_scatter(q_.X);
    last_lower_.resize(0), last_X_.resize(0);  // the vectors are sent again
  }

  // The scatter from S's layout (that of v) to this rank's unknowns, gathered from the
  // owners' rows; once a numbering.
  void make_scatter(Vec v) const {
    if (to_local_) return;
    Owned<IS, ISDestroy> from;
    check(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(petsc_of_.size()), petsc_of_.data(),
                          PETSC_COPY_VALUES, from.out()),
          "ISCreateGeneral");
    check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(petsc_of_.size()), &local_), "VecCreateSeq");
    check(VecScatterCreate(v, from, local_, nullptr, &to_local_), "VecScatterCreate");
  }

  // v's entries at this rank's unknowns (v in S's layout).
  Eigen::VectorXd values_at(Vec v) const {
    check(VecScatterBegin(to_local_, v, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(to_local_, v, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* a = nullptr;
    VecGetArrayRead(local_, &a);
    Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(a, static_cast<Eigen::Index>(petsc_of_.size()));
    VecRestoreArrayRead(local_, &a);
    return out;
  }

  // The distributed problem, the scatter and what was sent, dropped (a new numbering).
  void forget_layout() {
    q_.clear();
    if (diagonal_) VecDestroy(&diagonal_);
    if (to_local_) VecScatterDestroy(&to_local_);
    if (local_) VecDestroy(&local_);
    diagonal_ = nullptr, to_local_ = nullptr, local_ = nullptr;
    last_lower_.resize(0), last_X_.resize(0);
  }

  // r summed; the bounds, the warm start and its reaction written by every rank holding
  // the unknown (the same values) — the bounds only when they changed, the warm start
  // only when it is not the last solution, which the distributed vectors still hold.
  void assemble_vectors(const BoundQP& qp, const QPResult* warm) {
    const PetscInt n = static_cast<PetscInt>(petsc_of_.size());
    std::vector<Vec> sent = {q_.r};
    check(VecSet(q_.r, 0.0), "VecSet");
    check(VecSetValues(q_.r, n, petsc_of_.data(), qp.r.data(), ADD_VALUES), "VecSetValues");
    auto insert = [&](Vec v, const Eigen::VectorXd& x) {
      check(VecSetValues(v, n, petsc_of_.data(), x.data(), INSERT_VALUES), "VecSetValues");
      sent.push_back(v);
    };
    if (on_any_rank(last_lower_.size() != qp.size() || last_lower_ != qp.lower || last_upper_ != qp.upper)) {
      insert(q_.lower, qp.lower), insert(q_.upper, qp.upper);
      last_lower_ = qp.lower, last_upper_ = qp.upper;
    }
    const bool use_warm = warm && warm->X.size() == qp.size() && warm->reaction.size() == qp.size();
    const bool held = use_warm && last_X_.size() == qp.size() && warm->X == last_X_ &&
                      warm->reaction == last_reaction_;
    if (on_any_rank(!held)) {
      if (use_warm) {
        insert(q_.X, warm->X), insert(q_.reaction, warm->reaction);
      } else {
        check(VecSet(q_.X, 0.0), "VecSet"), check(VecSet(q_.reaction, 0.0), "VecSet");
      }
    }
    for (Vec v : sent) {
      check(VecAssemblyBegin(v), "VecAssemblyBegin");
      check(VecAssemblyEnd(v), "VecAssemblyEnd");
    }
  }

  // The kernel's KKT residual of the whole problem (qp/kkt.hpp): each rank takes its two
  // maxima over its unknowns (a shared one measured by every rank that holds it), with
  // the summed r, and the ranks their maxima.
  double kkt_over_ranks(const BoundQP& qp, const QPResult& result, const Eigen::VectorXd& D) const {
    BoundQP summed;  // this rank's unknowns with the summed r
    summed.r = values_at(q_.r), summed.lower = qp.lower, summed.upper = qp.upper;
    KKTMaxima m = kkt_maxima(summed, result.X, result.reaction, D);
    m.F = global_max(m.F), m.scale = global_max(m.scale);
    return m.residual();
  }

  std::vector<int> labels_;         // the whole problem's index of each of the subdomain's unknowns
  std::vector<int> global_;         // ... of each unknown of its QPs
  std::vector<PetscInt> petsc_of_;  // PETSc's index of each unknown of its QPs
  int n_ = 0;
  QPOptions options_;
  std::string name_;
  SolverChoice choice_;
  CheckedMatrices checked_;
  DistributedQP q_;
  Vec diagonal_ = nullptr;  // diag S, for the KKT measure and the active set
  mutable VecScatter to_local_ = nullptr;  // S's layout → this rank's unknowns (made when first needed)
  mutable Vec local_ = nullptr;
  Eigen::VectorXd last_lower_, last_upper_, last_X_, last_reaction_;  // as the distributed vectors hold them
};

}  // namespace

StepSolver* new_subdomain_step_solver(const std::vector<int>& global, const std::string& name,
                                      const QPOptions& options, const std::string& preconditioner) {
  const SolverChoice choice = choose_solver(name, options, preconditioner);
  session::start();
  session::every_rank_runs();
  return new SubdomainStepSolver(global, name, choice, options);
}

}  // namespace cdyn::petsc
