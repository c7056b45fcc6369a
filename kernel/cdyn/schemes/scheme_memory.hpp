// schemes/scheme_memory.hpp — what a time scheme remembers of the steps before, beyond
// the state (t, U, V): the last step QP's solution and active set (the warm start of
// the next), the three-level schemes' U^{n−1}, Newmark's acceleration, the discrete
// gradient's Ψ(qⁿ), the full-step reconstruction's warm start (eq. 14).
//
// With the State it is all a run needs to go on: TimeScheme::memory() hands it out,
// TimeScheme::restore() takes it back, in this process or in another one (the command
// line writes it into a checkpoint file; the kernel knows no file format).  restore()
// also clears the step solver's caches (StepSolver::clear): a scheme that restores the
// memory it has just handed out and a new scheme that restores the same memory then
// compute the same steps bit for bit, since the warm start is all that carries over.
#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "cdyn/qp/bound_qp.hpp"

namespace cdyn {

struct SchemeMemory {
  std::map<std::string, Eigen::VectorXd> vectors;
  std::map<std::string, double> numbers;
  std::map<std::string, std::vector<int>> indices;

  // The entry `name`; InputError (parameter "memory") when it is missing: the memory
  // comes from another scheme or problem.
  const Eigen::VectorXd& vector(const std::string& name) const;
  double number(const std::string& name) const;
  // A vector a scheme has only after its first step (U^{n−1}, Newmark's V̇ⁿ): stored when
  // not empty, read back as empty when absent.
  void store_if_any(const std::string& name, const Eigen::VectorXd& v);
  Eigen::VectorXd vector_or_empty(const std::string& name) const;
};

// A step QP's result as a warm start, under `prefix` (its X and active set, what the
// solvers start from); nothing for an empty one.
void store_warm_start(SchemeMemory& m, const std::string& prefix, const QPResult& result, bool present);
// Back: true and `result` filled when the memory holds one under `prefix`.
bool load_warm_start(const SchemeMemory& m, const std::string& prefix, QPResult& result);

}  // namespace cdyn
