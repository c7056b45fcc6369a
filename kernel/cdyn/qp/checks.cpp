// checks.cpp — input checks of a step QP, and their cache across time steps.
#include "cdyn/qp/checks.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/linalg/sparse_cholesky.hpp"

namespace cdyn {

namespace {

// Where the QP's S (or, in saddle form, A) keeps its values.
const double* values_of(const BoundQP& qp) { return qp.saddle ? qp.saddle->A.valuePtr() : qp.S.valuePtr(); }

void check_finite(const SparseMatrix& M, const std::string& what) {
  for (int j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it)
      if (!std::isfinite(it.value()))
        throw InputError("BoundQP: " + what + "(" + std::to_string(it.row()) + "," +
                         std::to_string(j) + ") = " + to_text(it.value()) + " is not finite");
}

// M − Mᵀ within 1e-10 of M's largest entry, an entry without its mirror measured against
// 0, in one pass over M and no copy of it: the columns are visited in order, and the
// mirror (j, i) of a lower entry (i, j), i > j, is the next unvisited upper entry of
// column i (the upper rows of a column come in increasing order, as the columns j that
// mirror them).  The check runs whenever a solver meets a new S — at every outer
// iteration of friction's loop on subdomains (qp/friction_ssn.cpp), where the transpose
// and difference made before took 9 % of the run.
void check_symmetric(const SparseMatrix& M, const std::string& what) {
  if (!M.isCompressed()) {
    SparseMatrix compressed = M;
    compressed.makeCompressed();
    return check_symmetric(compressed, what);
  }
  const int n = static_cast<int>(M.outerSize());
  const int* start = M.outerIndexPtr();
  const int* row = M.innerIndexPtr();
  const double* value = M.valuePtr();
  double max_entry = 0.0;
  for (int k = 0; k < start[n]; ++k) max_entry = std::max(max_entry, std::abs(value[k]));
  auto check = [&](int i, int j, double difference) {  // at (i, j): M_ij − M_ji
    if (std::abs(difference) > 1e-10 * max_entry)
      throw InputError("BoundQP: " + what + " is not symmetric: entry (" + std::to_string(i) + "," +
                       std::to_string(j) + ") differs from its transpose by " + to_text(difference));
  };
  std::vector<int> next(start, start + n);  // each column's next unmatched upper entry
  for (int j = 0; j < n; ++j)
    for (int k = start[j]; k < start[j + 1]; ++k) {
      const int i = row[k];
      if (i <= j) continue;  // (upper entries: matched from their mirrors' columns)
      // column i's upper entries above row j have no mirror
      for (; next[i] < start[i + 1] && row[next[i]] < j; ++next[i]) check(row[next[i]], i, value[next[i]]);
      const bool mirrored = next[i] < start[i + 1] && row[next[i]] == j;
      check(i, j, value[k] - (mirrored ? value[next[i]++] : 0.0));
    }
  for (int i = 0; i < n; ++i)  // the upper entries left unmatched
    for (; next[i] < start[i + 1] && row[next[i]] < i; ++next[i]) check(row[next[i]], i, value[next[i]]);
}

// The first check that entry i of r and the bounds fails, in the order of their messages.
enum class EntryCheck { Fine, RNotFinite, BoundNaN, NoFiniteValue, LowerAboveUpper };
EntryCheck failed_check(const BoundQP& qp, int i) {
  const double l = qp.lower[i], u = qp.upper[i];
  if (!std::isfinite(qp.r[i])) return EntryCheck::RNotFinite;
  if (std::isnan(l) || std::isnan(u)) return EntryCheck::BoundNaN;
  if (l == std::numeric_limits<double>::infinity() || u == -std::numeric_limits<double>::infinity())
    return EntryCheck::NoFiniteValue;
  if (l > u) return EntryCheck::LowerAboveUpper;
  return EntryCheck::Fine;
}

}  // namespace

void check_problem(const BoundQP& qp, bool matrices) {
  const int n = qp.size();
  if (qp.lower.size() != n || qp.upper.size() != n)
    throw InputError("BoundQP: r has " + std::to_string(n) + " entries but lower has " +
                     std::to_string(qp.lower.size()) + " and upper " + std::to_string(qp.upper.size()));
  const bool explicit_S = qp.S.rows() != 0 || qp.S.cols() != 0;
  if (explicit_S && qp.saddle)
    throw InputError("BoundQP: give either S or its saddle form, not both");
  if (!explicit_S && !qp.saddle && n > 0) throw InputError("BoundQP: neither S nor a saddle form is given");
  if (explicit_S) {
    if (qp.S.rows() != n || qp.S.cols() != n)
      throw InputError("BoundQP: S is " + std::to_string(qp.S.rows()) + "x" + std::to_string(qp.S.cols()) +
                       " but r has " + std::to_string(n) + " entries");
    if (matrices) {
      check_finite(qp.S, "S");
      check_symmetric(qp.S, "S");
    }
  } else if (qp.saddle) {
    const SaddleForm& f = *qp.saddle;
    const long m = f.C.rows();
    if (f.A.rows() != n || f.A.cols() != n)
      throw InputError("BoundQP: saddle block A is " + std::to_string(f.A.rows()) + "x" +
                       std::to_string(f.A.cols()) + " but r has " + std::to_string(n) + " entries");
    if (f.C.cols() != m || m == 0) throw InputError("BoundQP: saddle block C must be square and non-empty");
    if (f.B.rows() != m || f.B.cols() != n)
      throw InputError("BoundQP: saddle block B is " + std::to_string(f.B.rows()) + "x" +
                       std::to_string(f.B.cols()) + ", expected " + std::to_string(m) + "x" + std::to_string(n));
    if (!(std::isfinite(f.c) && f.c > 0)) throw InputError("BoundQP: saddle factor c = " + to_text(f.c) + " must be > 0");
    if (matrices) {
      check_finite(f.A, "A");
      check_finite(f.B, "B");
      check_finite(f.C, "C");
      check_symmetric(f.A, "A");
      check_symmetric(f.C, "C");
    }
  }
  // (called every step: the entries are checked shared among the threads, and the
  // message, with the index text, made only for the first failing one)
  bool all_fine = true;
#pragma omp parallel for schedule(static) reduction(&& : all_fine) if (3L * n >= kParallelWork)
  for (int i = 0; i < n; ++i) all_fine = all_fine && failed_check(qp, i) == EntryCheck::Fine;
  if (all_fine) return;
  int i = 0;
  while (failed_check(qp, i) == EntryCheck::Fine) ++i;
  const std::string at = std::string("[").append(std::to_string(i)).append("]");
  switch (failed_check(qp, i)) {
    case EntryCheck::RNotFinite:
      throw InputError("BoundQP: r" + at + " = " + to_text(qp.r[i]) + " is not finite");
    case EntryCheck::BoundNaN:
      throw InputError("BoundQP: bound" + at + " is NaN");
    case EntryCheck::NoFiniteValue:
      throw InputError("BoundQP: bounds" + at + " exclude every finite value: the constraint set is empty");
    default:
      throw InputError("BoundQP: lower" + at + " = " + to_text(qp.lower[i]) + " > upper" + at + " = " +
                       to_text(qp.upper[i]) + ": the constraint set is empty");
  }
}

// The same nonzero name as the last call's, for matrices still stored where they were
// (a QP whose S was reassigned without a new name is compared, not trusted).
bool CheckedMatrices::named_as_last(const BoundQP& qp) const {
  return valid_ && qp.matrices_id != 0 && qp.matrices_id == id_ && values_of(qp) == values_;
}

bool CheckedMatrices::check(const BoundQP& qp, bool positive_definite, const std::string& solver) {
  if (named_as_last(qp)) {
    check_problem(qp, false);
    return false;
  }
  bool same = valid_;
  if (same && qp.saddle)
    same = S_.size() == 0 && qp.saddle->c == c_ && same_matrix(qp.saddle->A, A_) && same_matrix(qp.saddle->B, B_) &&
           same_matrix(qp.saddle->C, C_);
  else if (same)
    same = A_.size() == 0 && same_matrix(qp.S, S_);
  check_problem(qp, !same);
  const auto name = [&] {  // (only matrices that passed the checks are named)
    id_ = qp.matrices_id;
    values_ = values_of(qp);
  };
  if (same) {
    name();
    return false;
  }
  valid_ = false;
  if (qp.saddle) {
    A_ = qp.saddle->A;
    B_ = qp.saddle->B;
    C_ = qp.saddle->C;
    c_ = qp.saddle->c;
    S_ = SparseMatrix();
  } else {
    if (positive_definite && qp.size() > 0) check_positive_definite(qp.S, solver + ": S");
    S_ = qp.S;
    A_ = B_ = C_ = SparseMatrix();
  }
  for (SparseMatrix* M : {&S_, &A_, &B_, &C_}) M->makeCompressed();
  valid_ = true;
  name();
  return true;
}

}  // namespace cdyn
