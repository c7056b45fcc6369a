// reduced_system.cpp — what the reduced systems of an active-set step share: the
// elimination of the held unknowns in a matrix's own pattern, the default reaction, the
// tolerance of an inexact solve, and a factor's counted factorization and row updates.
#include "cdyn/qp/pdas/reduced_system.hpp"

#include <algorithm>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/linalg/sparse_cholesky.hpp"

namespace cdyn {

namespace {

// CG's stopping tolerance for a PDAS iterate that is not yet the solution, relative to
// the solution's scale.  Measured on the membrane at n = 160 (docs/performance.md (a)):
// 1e-3 costs more PDAS iterations (decisions on too rough an X), 1e-5 and 1e-6 more CG
// iterations per step; 1e-4 is the cheapest.
constexpr double kLooseSolve = 1e-4;

}  // namespace

SolveTolerance::SolveTolerance(const BoundQP& qp, const Eigen::VectorXd& D, double tol)
    : tol_(tol), r_scale_(max_abs(qp.r, &D)) {}

double SolveTolerance::operator()(const Eigen::VectorXd& held_values, bool tight) const {
  return (*this)(max_abs(held_values), tight);
}

double SolveTolerance::operator()(double held_max, bool tight) const {
  const double scale = std::max(r_scale_, held_max);
  return (tight ? 0.5 * tol_ : std::max(0.5 * tol_, kLooseSolve)) * scale;
}

void ReducedSystem::reaction(const BoundQP&, const QuadraticForm& form, const Eigen::VectorXd& X, const HeldSet&,
                             Eigen::VectorXd& lam, const Iterate*) const {
  lam = form.gradient(X);
}

void replace_held_by_identity(const SparseMatrix& M, const HeldSet& held, SparseMatrix& out) {
  const int n = static_cast<int>(held.size());
  const int* outer = M.outerIndexPtr();
  const int* inner = M.innerIndexPtr();
  const double* m = M.valuePtr();
  double* v = out.valuePtr();
#pragma omp parallel for schedule(static) if (M.nonZeros() >= kParallelWork)
  for (int j = 0; j < M.outerSize(); ++j) {
    const bool aj = j < n && held[j];
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      const int i = inner[p];
      const bool ai = i < n && held[i];
      v[p] = (ai || aj) ? (i == j ? 1.0 : 0.0) : m[p];
    }
  }
}

void copy_held_values(const HeldSet& held, const Eigen::VectorXd& value, Eigen::VectorXd& v) {
  const long n = static_cast<long>(held.size());
#pragma omp parallel for schedule(static) if (n >= kParallelWork)
  for (long j = 0; j < n; ++j)
    if (held[j]) v[j] = value[j];
}

void factorize_counted(SparseCholesky& factor, const SparseMatrix& matrix, const std::string& what,
                       PDASCounters& counters, const std::vector<int>* unknowns) {
  ScopeTimer timer(counters.factorization_s);
  const int minor = factor.factorize(matrix);
  ++counters.factorizations;
  if (minor >= 0)
    throw NumericalError("pdas: " + what + " at unknown " + std::to_string(unknowns ? (*unknowns)[minor] : minor) + ")");
}

bool update_held(SparseCholesky& factor, const SparseMatrix& S, HeldSet& held, const std::vector<int>& to_delete,
                 const std::vector<int>& to_add, double& flops) {
  for (int i : to_delete) {
    factor.replace_by_identity(i);
    flops += factor.modification_flops();
    held[i] = 1;
  }
  std::vector<char> keep(held.size());
  for (std::size_t i = 0; i < held.size(); ++i) keep[i] = !held[i];
  for (int i : to_add) {
    keep[i] = 1;
    if (!factor.restore(i, S, keep)) return false;
    flops += factor.modification_flops();
    held[i] = 0;
  }
  return true;
}

}  // namespace cdyn
