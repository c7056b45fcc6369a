// problems/constrained_problem.cpp — load with lifting, full-field energy, violation, and the
// optional change of basis U_f = R U' (see problems/constrained_problem.hpp).
#include "cdyn/problems/constrained_problem.hpp"

#include <algorithm>

#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

const ConstrainedProblem::CachedLoad& ConstrainedProblem::cached_load(double t) const {
  for (int k = 0; k < load_cache_size_; ++k)
    if (load_is_constant || load_cache_[k].t == t) return load_cache_[k];
  CachedLoad& c = load_cache_[load_cache_next_];  // the oldest
  load_cache_next_ = (load_cache_next_ + 1) % static_cast<int>(load_cache_.size());
  load_cache_size_ = std::min(load_cache_size_ + 1, static_cast<int>(load_cache_.size()));
  c.t = t;
  c.full = L_full(t);
  // (A U_D)_f once: U_D is constant, and with a load in t this product with the whole A
  // was 7 % of a linear step of the membrane (n = 160)
  if (lift_force_.size() != n_free()) lift_force_ = local(bc->restrict(Eigen::VectorXd(A_full * UD)));
  c.free = local(bc->restrict(c.full)) - lift_force_;
  return c;
}

const Eigen::VectorXd& ConstrainedProblem::full_load(double t) const { return cached_load(t).full; }

const Eigen::VectorXd& ConstrainedProblem::load(double t) const { return cached_load(t).free; }

Eigen::VectorXd ConstrainedProblem::full(const Eigen::VectorXd& Uf) const {
  return R ? bc->extend(*R * Uf, UD) : bc->extend(Uf, UD);  // (no copy of Uf without R)
}

Eigen::VectorXd ConstrainedProblem::global(const Eigen::VectorXd& X) const {
  if (!R) return X;
  return *R * X;
}

Eigen::VectorXd ConstrainedProblem::local(const Eigen::VectorXd& X) const {
  if (!R) return X;
  return R->transpose() * X;
}

double ConstrainedProblem::potential_energy(const Eigen::VectorXd& Uf, double t) const {
  const Eigen::VectorXd U = full(Uf);
  return 0.5 * dot(U, symmetric_times(A_full, U)) - dot(full_load(t), U);
}

void ConstrainedProblem::bounds(double t, Eigen::VectorXd& lower_t, Eigen::VectorXd& upper_t) const {
  if (!moving_bounds) {
    lower_t = lower;
    upper_t = upper;
    return;
  }
  lower_t = lower;  // (the unconstrained entries keep their ±inf)
  upper_t = upper;
  moving_bounds(t, lower_t, upper_t);
}

double ConstrainedProblem::max_violation(const Eigen::VectorXd& Uf, double t) const {
  const Eigen::VectorXd* lo = &lower;
  const Eigen::VectorXd* up = &upper;
  Eigen::VectorXd lower_t, upper_t;
  if (moving_bounds) {
    bounds(t, lower_t, upper_t);
    lo = &lower_t, up = &upper_t;
  }
  // (each run's check after every step: `omp simd` lets the maximum run in vector
  // partial maxima, exact in any order, instead of a chain through one register)
  const double* l = lo->data();
  const double* u = up->data();
  const double* x = Uf.data();
  const int* c = constrained.data();
  const long m = static_cast<long>(constrained.size());
  double v = 0.0;
#pragma omp simd reduction(max : v)
  for (long k = 0; k < m; ++k) v = std::max(v, std::max(l[c[k]] - x[c[k]], x[c[k]] - u[c[k]]));
  return v;
}

std::vector<std::vector<int>> bubble_unknowns(const ConstrainedProblem& p) {
  const FESpace& W = *p.W;
  std::vector<std::vector<int>> blocks;
  if (W.element() != Element::P1Bubble) return blocks;
  const int bubble = W.dim() + 1;  // the cell's local dof after its vertices
  for (int c = 0; c < W.mesh().n_cells(); ++c) {
    std::vector<int> block;
    for (int k = 0; k < W.components(); ++k) {
      const int i = p.bc->free_index(W.dof(W.cell_dofs(c)[bubble], k));
      if (i >= 0) block.push_back(i);
    }
    if (!block.empty()) blocks.push_back(std::move(block));
  }
  return blocks;
}

}  // namespace cdyn
