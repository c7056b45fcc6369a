// kernel/plugins/petsc/distributed_qp.hpp — the step QP of qp/bound_qp.hpp spread over the MPI
// ranks, and the protocol by which rank 0 hands it out.
//
//     min_X ½ XᵀSX − rᵀX,   lower ≤ X ≤ upper,
//
// with S an MPIAIJ matrix and r, lower, upper, X PETSc vectors, each rank owning a
// contiguous block of rows of a partitioned numbering.  Rank 0 holds the problem as the serial kernel built it and scatters
// the rows (S is symmetric, so its compressed columns are its compressed rows), which a
// graph partitioner then deals out again so that each rank's rows are coupled mostly
// among themselves; S is sent again only when it changed (a new dt, a new mesh), the
// vectors at every step.
// The solution is gathered back to rank 0, which measures it with the kernel's one
// KKT residual (qp/kkt.hpp), as it does every solver's.
//
// Internal to the plugin (kernel/plugins/petsc/), whose headers alone include PETSc's.
#pragma once

#include <petscksp.h>

#include <string>
#include <vector>

#include "cdyn/qp/bound_qp.hpp"

namespace cdyn::petsc {

// A PETSc error code as an exception: NumericalError naming the call.
void check(PetscErrorCode code, const char* call);

// The largest of a local number over the ranks, on every rank (collective).
double global_max(double local);

// A PETSc object of a solve's own, destroyed when the solve leaves, also when a failure
// is thrown on the way (every rank throws the same failure: the destruction stays
// collective).  E.g. Owned<Vec, VecDestroy> b; VecDuplicate(r, b.out()); VecCopy(r, b).
template <class T, PetscErrorCode (*Destroy)(T*)>
class Owned {
 public:
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() { Destroy(&object_); }
  T* out() { return &object_; }  // for the creating call
  operator T() const { return object_; }

 private:
  T object_ = nullptr;
};

// What rank 0 asks of the others (session.hpp).
enum class Command : int { solve = 1, clear = 2, quit = 3 };
void send(Command command);  // rank 0
Command receive();           // ranks ≥ 1

// The distributed solvers (docs/distributed.md), and the preconditioners of the Krylov
// solves inside them.
enum class Algorithm : int { pdas = 0, tao_tron, tao_gpcg, tao_bqnls, tao_bncg, snesvi };
enum class Preconditioner : int { gamg = 0, hypre, jacobi };

// Everything a solve needs besides the data, the same on every rank.
struct SolveSettings {
  int n = 0;                  // rows of the matrix sent: the unknowns, and Z's in saddle form
  int saddle_rows = 0;        // in saddle form, the m rows of Z (0: S explicit)
  int matrix_changed = 0;     // S is sent (again)
  int warm = 0;               // a warm start X (and its reaction) is sent
  Algorithm algorithm = Algorithm::pdas;
  Preconditioner pc = Preconditioner::gamg;
  double tol = 1e-10;         // on the KKT residual (qp/kkt.hpp)
  int max_iterations = 0;     // 0: the algorithm's default
};

// The problem on this rank, kept across steps (one per process).
class DistributedQP {
 public:
  DistributedQP() = default;
  DistributedQP(const DistributedQP&) = delete;
  DistributedQP& operator=(const DistributedQP&) = delete;
  ~DistributedQP() { clear(); }

  // Collective.  Rank 0 gives the settings (broadcast) and its qp and warm start (the
  // other ranks pass nullptr and receive theirs).  In saddle form qp is the extended
  // problem (S the symmetric saddle matrix K of base/sparse.hpp, the Z rows unbounded)
  // and D the held-set rule's scaling (sent with the matrix; diag(S) otherwise).
  void receive(SolveSettings& settings, const BoundQP* qp, const QPResult* warm,
               const Eigen::VectorXd* D = nullptr);
  // Collective: X on rank 0 (empty elsewhere).
  Eigen::VectorXd gather_solution() const;
  // Drops S and every vector (collective when they exist).
  void clear();
  bool has_matrix() const { return S != nullptr; }

  // The problem in the partitioned numbering: this rank's rows are [first, last).
  Mat S = nullptr;
  Vec r = nullptr, lower = nullptr, upper = nullptr;  // ±infinity where unbounded
  Vec X = nullptr;         // the warm start on entry of a solve, the solution on exit
  Vec reaction = nullptr;  // λ = S X − r of the warm start (when settings.warm), else 0
  Vec D = nullptr;         // in saddle form, the held-set rule's scaling (qp/kkt.hpp)
  PetscInt first = 0, last = 0;
  int n = 0;
  // In saddle form, K̃'s factor, kept across iterations and steps while the held set is
  // the one factorized (distributed_pdas.cpp).
  Mat K_held = nullptr;
  KSP factor = nullptr;
  std::vector<signed char> factored_held;

 private:
  // S in natural blocks of rows, as scattered, is re-partitioned by PT-Scotch's graph
  // partitioner (on more than one rank): the unknowns are numbered as the kernel built
  // them, e.g. component by component, and equal blocks of that numbering cut every
  // coupling (measured: 1.7 MB sent per product on the 32³ cube, the flops 3.7 times
  // larger on one rank than on the other).  Sets S and rows.
  void partition(Mat S_natural);
  IS rows = nullptr;             // the natural indices of this rank's rows, increasing
  Vec natural = nullptr;         // a vector in natural blocks
  VecScatter to_rows = nullptr;  // natural blocks → partitioned rows
};

// The process's distributed problem, and who sent its S last (rank 0's solvers compare
// with it to know whether S must be sent).
DistributedQP& the_distributed_qp();
struct MatrixOwner {
  const void* solver = nullptr;
  unsigned long version = 0;
};
MatrixOwner& matrix_owner();

// Runs settings.algorithm on q (collective); returns the number of iterations made
// (for the TAO and SNESVI algorithms, theirs plus the active-set iterations of the
// crossover that brings the result to tol, as for Ipopt in the serial kernel).
int solve_collectively(DistributedQP& q, const SolveSettings& settings);

// The algorithms (distributed_pdas.cpp, tao_solve.cpp, snesvi_solve.cpp).
int distributed_pdas(DistributedQP& q, const SolveSettings& settings, bool warm);
int tao_solve(DistributedQP& q, const SolveSettings& settings);
int snesvi_solve(DistributedQP& q, const SolveSettings& settings);

// The preconditioner of a Krylov solver, then PETSc's options (PETSC_OPTIONS, prefix
// -cdyn_) on top.  fixed_size: the solver sees a sequence of matrices of S's size and
// pattern (pdas's reduced systems), so GAMG keeps its first prolongation; TAO's and
// SNESVI's systems change size with the free set, and may not.
void configure_krylov(KSP ksp, Preconditioner pc, bool fixed_size);

// X projected on the box lower ≤ X ≤ upper (a start that satisfies the bounds).
void project_on_box(DistributedQP& q);

// For TAO and SNESVI: copies of the bounds in PETSc's convention (±PETSC_INFINITY for
// ±∞; the caller destroys them), and X projected on the box.
void petsc_bounds(DistributedQP& q, Vec* lower, Vec* upper);

}  // namespace cdyn::petsc
