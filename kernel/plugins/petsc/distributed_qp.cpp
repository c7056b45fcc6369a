// distributed_qp.cpp — scattering the step QP from rank 0 and gathering its solution;
// see kernel/plugins/petsc/distributed_qp.hpp.
#include "distributed_qp.hpp"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "cdyn/base/error.hpp"

namespace cdyn::petsc {

namespace {

MPI_Comm world() { return PETSC_COMM_WORLD; }

int comm_rank() {
  int r = 0;
  MPI_Comm_rank(world(), &r);
  return r;
}

// PETSc's default split of n rows over the ranks (PetscSplitOwnership): the first row of
// each rank, and n at the end.
std::vector<int> row_ranges(int n) {
  int p = 1;
  MPI_Comm_size(world(), &p);
  std::vector<int> first(p + 1, 0);
  for (int k = 0; k < p; ++k) first[k + 1] = first[k] + n / p + (k < n % p ? 1 : 0);
  return first;
}

// Rank 0's vector v (size n) into the distributed x, by blocks of rows.
void scatter(const Eigen::VectorXd* v, const std::vector<int>& first, Vec x) {
  const int p = static_cast<int>(first.size()) - 1;
  std::vector<int> counts(p), displs(p);
  for (int k = 0; k < p; ++k) counts[k] = first[k + 1] - first[k], displs[k] = first[k];
  PetscScalar* local = nullptr;
  check(VecGetArray(x, &local), "VecGetArray");
  MPI_Scatterv(v ? v->data() : nullptr, counts.data(), displs.data(), MPI_DOUBLE, local, counts[comm_rank()],
               MPI_DOUBLE, 0, world());
  check(VecRestoreArray(x, &local), "VecRestoreArray");
}

Vec new_vector(int local, int n) {
  Vec v = nullptr;
  check(VecCreateMPI(world(), local, n, &v), "VecCreateMPI");
  return v;
}

void destroy(Vec& v) {
  if (v) VecDestroy(&v);
  v = nullptr;
}

}  // namespace

double global_max(double local) {
  double out = 0.0;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, world());
  return out;
}

void check(PetscErrorCode code, const char* call) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw NumericalError(std::string("PETSc: ") + call + " failed (" + (text ? text : "error " + std::to_string(code)) +
                       ")");
}

void send(Command command) {
  int c = static_cast<int>(command);
  MPI_Bcast(&c, 1, MPI_INT, 0, world());
}

Command receive() {
  int c = 0;
  MPI_Bcast(&c, 1, MPI_INT, 0, world());
  return static_cast<Command>(c);
}

DistributedQP& the_distributed_qp() {
  static DistributedQP q;
  return q;
}

MatrixOwner& matrix_owner() {
  static MatrixOwner owner;
  return owner;
}

void DistributedQP::receive(SolveSettings& settings, const BoundQP* qp, const QPResult* warm,
                            const Eigen::VectorXd* D_saddle) {
  MPI_Bcast(&settings, sizeof settings, MPI_BYTE, 0, world());
  const std::vector<int> first_row = row_ranges(settings.n);
  const int me = comm_rank(), p = static_cast<int>(first_row.size()) - 1;
  const int local = first_row[me + 1] - first_row[me];
  const bool new_matrix = settings.matrix_changed || settings.n != n;
  if (new_matrix) {
    clear();
    n = settings.n;
    // The rows of S: per-row counts, then column indices and values by blocks.
    std::vector<int> row_nnz(qp ? n : 0), counts(p), displs(p);
    if (qp) {
      const int* colptr = qp->S.outerIndexPtr();
      for (int i = 0; i < n; ++i) row_nnz[i] = colptr[i + 1] - colptr[i];
      for (int k = 0; k < p; ++k) counts[k] = colptr[first_row[k + 1]] - colptr[first_row[k]], displs[k] = colptr[first_row[k]];
    }
    MPI_Bcast(counts.data(), p, MPI_INT, 0, world());
    std::vector<int> row_counts(p), row_displs(p);
    for (int k = 0; k < p; ++k) row_counts[k] = first_row[k + 1] - first_row[k], row_displs[k] = first_row[k];
    std::vector<PetscInt> i(local + 1, 0), j(counts[me]);
    std::vector<int> my_rows(local);
    MPI_Scatterv(qp ? row_nnz.data() : nullptr, row_counts.data(), row_displs.data(), MPI_INT, my_rows.data(), local,
                 MPI_INT, 0, world());
    for (int row = 0; row < local; ++row) i[row + 1] = i[row] + my_rows[row];
    std::vector<PetscScalar> a(counts[me]);
    MPI_Scatterv(qp ? qp->S.innerIndexPtr() : nullptr, counts.data(), displs.data(), MPI_INT, j.data(), counts[me],
                 MPI_INT, 0, world());
    MPI_Scatterv(qp ? qp->S.valuePtr() : nullptr, counts.data(), displs.data(), MPI_DOUBLE, a.data(), counts[me],
                 MPI_DOUBLE, 0, world());
    Mat S_natural = nullptr;
    check(MatCreateMPIAIJWithArrays(world(), local, local, n, n, i.data(), j.data(), a.data(), &S_natural),
          "MatCreateMPIAIJWithArrays");
    partition(S_natural);
    check(MatSetOption(S, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    // (the saddle matrix is indefinite: MUMPS must not take it for SPD)
    if (settings.saddle_rows == 0) check(MatSetOption(S, MAT_SPD, PETSC_TRUE), "MatSetOption");
    PetscInt mine = 0;
    check(MatGetLocalSize(S, &mine, nullptr), "MatGetLocalSize");
    check(MatGetOwnershipRange(S, &first, &last), "MatGetOwnershipRange");
    r = new_vector(mine, n), lower = new_vector(mine, n), upper = new_vector(mine, n);
    X = new_vector(mine, n), reaction = new_vector(mine, n);
    natural = new_vector(local, n);
    check(VecScatterCreate(natural, rows, r, nullptr, &to_rows), "VecScatterCreate");
    if (settings.saddle_rows > 0) D = new_vector(mine, n);
  }
  // rank 0's vector → the natural blocks → this rank's partitioned rows
  auto distribute = [&](const Eigen::VectorXd* v, Vec x) {
    scatter(v, first_row, natural);
    check(VecScatterBegin(to_rows, natural, x, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(to_rows, natural, x, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  };
  if (new_matrix && settings.saddle_rows > 0) distribute(D_saddle, D);
  distribute(qp ? &qp->r : nullptr, r);
  distribute(qp ? &qp->lower : nullptr, lower);
  distribute(qp ? &qp->upper : nullptr, upper);
  if (settings.warm) {
    distribute(warm ? &warm->X : nullptr, X);
    distribute(warm ? &warm->reaction : nullptr, reaction);
  } else {
    check(VecSet(X, 0.0), "VecSet");
    check(VecSet(reaction, 0.0), "VecSet");
  }
}

void DistributedQP::partition(Mat S_natural) {
  int p = 1;
  MPI_Comm_size(world(), &p);
  PetscInt local = 0, begin = 0;
  check(MatGetLocalSize(S_natural, &local, nullptr), "MatGetLocalSize");
  check(MatGetOwnershipRange(S_natural, &begin, nullptr), "MatGetOwnershipRange");
  if (p == 1) {  // nothing to balance: the natural order
    check(ISCreateStride(world(), local, begin, 1, &rows), "ISCreateStride");
    S = S_natural;
    return;
  }
  MatPartitioning part = nullptr;
  IS owner = nullptr;
  check(MatPartitioningCreate(world(), &part), "MatPartitioningCreate");
  check(MatPartitioningSetAdjacency(part, S_natural), "MatPartitioningSetAdjacency");
  check(MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType");
  check(MatPartitioningSetFromOptions(part), "MatPartitioningSetFromOptions");
  check(MatPartitioningApply(part, &owner), "MatPartitioningApply");  // the new rank of each local row
  check(ISBuildTwoSided(owner, nullptr, &rows), "ISBuildTwoSided");   // the rows this rank receives
  check(ISSort(rows), "ISSort");
  check(MatCreateSubMatrix(S_natural, rows, rows, MAT_INITIAL_MATRIX, &S), "MatCreateSubMatrix");
  ISDestroy(&owner);
  MatPartitioningDestroy(&part);
  MatDestroy(&S_natural);
}

Eigen::VectorXd DistributedQP::gather_solution() const {
  const std::vector<int> first_row = row_ranges(n);
  const int p = static_cast<int>(first_row.size()) - 1;
  std::vector<int> counts(p), displs(p);
  for (int k = 0; k < p; ++k) counts[k] = first_row[k + 1] - first_row[k], displs[k] = first_row[k];
  Eigen::VectorXd out = comm_rank() == 0 ? Eigen::VectorXd(n) : Eigen::VectorXd();
  // this rank's partitioned rows → the natural blocks → rank 0
  check(VecScatterBegin(to_rows, X, natural, INSERT_VALUES, SCATTER_REVERSE), "VecScatterBegin");
  check(VecScatterEnd(to_rows, X, natural, INSERT_VALUES, SCATTER_REVERSE), "VecScatterEnd");
  const PetscScalar* local = nullptr;
  check(VecGetArrayRead(natural, &local), "VecGetArrayRead");
  MPI_Gatherv(local, counts[comm_rank()], MPI_DOUBLE, out.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
              world());
  check(VecRestoreArrayRead(natural, &local), "VecRestoreArrayRead");
  return out;
}

void DistributedQP::clear() {
  if (S) MatDestroy(&S);
  S = nullptr;
  for (Vec* v : {&r, &lower, &upper, &X, &reaction, &D, &natural}) destroy(*v);
  if (factor) KSPDestroy(&factor);
  if (K_held) MatDestroy(&K_held);
  factor = nullptr, K_held = nullptr;
  factored_held.clear();
  if (to_rows) VecScatterDestroy(&to_rows);
  if (rows) ISDestroy(&rows);
  to_rows = nullptr, rows = nullptr;
  n = 0;
}

void configure_krylov(KSP ksp, Preconditioner pc_type, bool fixed_size) {
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  switch (pc_type) {
    case Preconditioner::gamg:
      check(PCSetType(pc, PCGAMG), "PCSetType");
      // the reduced systems of successive iterations share S's pattern: keep the
      // prolongation of the first (PETSc rebuilds only the coarse operators)
      if (fixed_size) check(PCGAMGSetReuseInterpolation(pc, PETSC_TRUE), "PCGAMGSetReuseInterpolation");
      break;
    case Preconditioner::hypre:
      check(PCSetType(pc, PCHYPRE), "PCSetType");
      break;
    case Preconditioner::jacobi:
      check(PCSetType(pc, PCJACOBI), "PCSetType");
      break;
  }
  check(KSPSetOptionsPrefix(ksp, "cdyn_"), "KSPSetOptionsPrefix");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
}

void project_on_box(DistributedQP& q) {
  check(VecPointwiseMax(q.X, q.X, q.lower), "VecPointwiseMax");
  check(VecPointwiseMin(q.X, q.X, q.upper), "VecPointwiseMin");
}

void petsc_bounds(DistributedQP& q, Vec* lower, Vec* upper) {
  for (auto [from, to] : {std::pair{q.lower, lower}, std::pair{q.upper, upper}}) {
    check(VecDuplicate(from, to), "VecDuplicate");
    check(VecCopy(from, *to), "VecCopy");
    PetscScalar* b = nullptr;
    PetscInt m = 0;
    check(VecGetLocalSize(*to, &m), "VecGetLocalSize");
    check(VecGetArray(*to, &b), "VecGetArray");
    for (PetscInt i = 0; i < m; ++i)
      if (std::isinf(b[i])) b[i] = b[i] > 0 ? PETSC_INFINITY : PETSC_NINFINITY;
    check(VecRestoreArray(*to, &b), "VecRestoreArray");
  }
  project_on_box(q);
}

int solve_collectively(DistributedQP& q, const SolveSettings& settings) {
  switch (settings.algorithm) {
    case Algorithm::pdas:
      return distributed_pdas(q, settings, settings.warm != 0);
    case Algorithm::snesvi:
      return snesvi_solve(q, settings);
    default:
      return tao_solve(q, settings);
  }
}

}  // namespace cdyn::petsc
