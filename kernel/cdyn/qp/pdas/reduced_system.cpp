// reduced_system.cpp — what the two reduced systems of an active-set step share: the
// elimination of the held unknowns in a matrix's own pattern, the default reaction, and
// the tolerance of an inexact solve.
#include "cdyn/qp/pdas/reduced_system.hpp"

#include <algorithm>

#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

namespace {

// CG's stopping tolerance for a PDAS iterate that is not yet the solution, relative to
// the solution's scale.  Measured on the membrane at n = 160 (docs/performance.md (a)):
// 1e-3 costs more PDAS iterations (decisions on too rough an X), 1e-5 and 1e-6 more CG
// iterations per step; 1e-4 is the cheapest.
constexpr double kLooseSolve = 1e-4;

}  // namespace

SolveTolerance::SolveTolerance(const BoundQP& qp, const Eigen::VectorXd& D, double tol)
    : tol_(tol), r_scale_(qp.r.cwiseQuotient(D).lpNorm<Eigen::Infinity>()) {}

double SolveTolerance::operator()(const Eigen::VectorXd& held_values, bool tight) const {
  const double scale = std::max(r_scale_, held_values.lpNorm<Eigen::Infinity>());
  return (tight ? 0.5 * tol_ : std::max(0.5 * tol_, kLooseSolve)) * scale;
}

Eigen::VectorXd ReducedSystem::reaction(const BoundQP& qp, const QuadraticForm& form, const Eigen::VectorXd& X,
                                        const HeldSet&) const {
  return form.apply(X) - qp.r;
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
  for (std::size_t j = 0; j < held.size(); ++j)
    if (held[j]) v[j] = value[j];
}

}  // namespace cdyn
