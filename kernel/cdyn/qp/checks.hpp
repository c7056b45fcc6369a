// checks.hpp — the input checks every step solver makes on a QP (qp/bound_qp.hpp):
// sizes, finite data, symmetry, a non-empty box, and (once per distinct S) positive
// definiteness.
#pragma once

#include <string>

#include "cdyn/qp/bound_qp.hpp"

namespace cdyn {

// Throws InputError when sizes disagree, S (or A, B, C) or r contain NaN/Inf, S is not
// symmetric, a bound is NaN, lower > upper somewhere (an empty feasible set), or both
// or neither of S and saddle are given.  matrices = false skips the O(nnz) checks of
// the matrices (see CheckedMatrices).
void check_problem(const BoundQP& qp, bool matrices = true);

// check_problem() (and, on request, check_positive_definite() of an explicit S) for a
// solver object that lives across time steps: the matrices are checked only when they
// differ from those of the last call (pattern or values), so a time loop with an
// unchanged S pays for the checks once.  Matrices named as the last call's
// (BoundQP::matrices_id) are the last call's, not compared.
class CheckedMatrices {
 public:
  // Returns true when the matrices were new (and have now been checked).
  bool check(const BoundQP& qp, bool positive_definite, const std::string& solver);

 private:
  bool named_as_last(const BoundQP& qp) const;
  bool valid_ = false;
  SparseMatrix S_, A_, B_, C_;
  double c_ = 0.0;
  std::uint64_t id_ = 0;            // the last call's BoundQP::matrices_id
  const double* values_ = nullptr;  // and where its S's (or A's) values were
};

}  // namespace cdyn
