// sparse_cholesky.cpp — CHOLMOD's analysis, factorization, solve and row updates,
// reading Eigen's compressed columns in place.
#include "cdyn/linalg/sparse_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/linalg/supernodal_solve.hpp"
#include "cdyn/linalg/threads.hpp"

namespace cdyn {

struct SparseCholesky::Impl {
  cholmod_common common;
  cholmod_factor* symbolic = nullptr;  // the analysis, kept to start each factorization from
  cholmod_factor* L = nullptr;         // the current numeric factor
  cholmod_factor* kept = nullptr;      // a copy of an earlier one (keep(), use_kept())
  std::vector<int> outer, inner;       // pattern of the analysed matrix
  std::vector<int> position;           // position[i] = row of L holding original unknown i
  double flops = 0.0;                  // of a numeric factorization (the analysis's count)
  double lnz = 0.0;                    // entries of L (the analysis's count)
  mutable cholmod_dense* X = nullptr;  // solve workspaces (cholmod_solve2)
  mutable cholmod_dense* Y = nullptr;
  mutable cholmod_dense* E = nullptr;
  // A supernodal factor's sweeps by subtrees (linalg/supernodal_solve.hpp), cut for the
  // thread count of the last solve; reset by each analysis.
  mutable std::unique_ptr<SupernodalSolve> sweeps;
  int sweeps_suit = -1;  // SupernodalSolve::suits the analysed pattern (−1: not asked yet)
  mutable std::unique_ptr<SupernodalPaths> paths;  // for unit_forward on a supernodal factor
  mutable std::vector<double> z;                   // unit_forward's on a simplicial one (zero between calls)
  mutable Eigen::VectorXd y;  // the permuted right-hand side

  Impl() {
    cholmod_start(&common);
    common.print = 0;
    common.error_handler = nullptr;
    // LLᵀ also in the simplicial case: LDLᵀ would factorize an indefinite S without
    // complaint, LLᵀ stops at the first non-positive pivot.  (cholmod_rowadd/rowdel
    // convert the factor to simplicial LDLᵀ themselves.)
    common.final_ll = 1;
  }
  ~Impl() {
    free_factor(L);
    free_factor(kept);
    free_factor(symbolic);
    cholmod_free_dense(&X, &common);
    cholmod_free_dense(&Y, &common);
    cholmod_free_dense(&E, &common);
    cholmod_finish(&common);
  }
  void free_factor(cholmod_factor*& F) {
    if (F) cholmod_free_factor(&F, &common);
    F = nullptr;
  }
  void copy_factor(const cholmod_factor* from, cholmod_factor*& to) {
    free_factor(to);
    to = cholmod_copy_factor(const_cast<cholmod_factor*>(from), &common);
    check("copy_factor");
  }
  // A view of S, lower triangle used (stype = −1); the arrays are Eigen's.
  static cholmod_sparse view(const SparseMatrix& S) {
    cholmod_sparse A;
    std::memset(&A, 0, sizeof A);
    A.nrow = S.rows();
    A.ncol = S.cols();
    A.nzmax = S.nonZeros();
    A.p = const_cast<int*>(S.outerIndexPtr());
    A.i = const_cast<int*>(S.innerIndexPtr());
    A.x = const_cast<double*>(S.valuePtr());
    A.stype = -1;
    A.itype = CHOLMOD_INT;
    A.xtype = CHOLMOD_REAL;
    A.dtype = CHOLMOD_DOUBLE;
    A.sorted = 1;
    A.packed = 1;
    return A;
  }
  static SupernodalFactor supernodal(const cholmod_factor& F) {
    SupernodalFactor s;
    s.n = static_cast<int>(F.n);
    s.nsuper = static_cast<int>(F.nsuper);
    s.super = static_cast<const int*>(F.super);
    s.pi = static_cast<const int*>(F.pi);
    s.px = static_cast<const int*>(F.px);
    s.s = static_cast<const int*>(F.s);
    s.x = static_cast<const double*>(F.x);
    return s;
  }
  // Our sweeps by subtrees when L is supernodal LLᵀ with narrow supernodes, cut for the
  // kernel's thread count; null: CHOLMOD's solve.
  const SupernodalSolve* subtree_sweeps() {
    if (!L->is_super || !L->is_ll) return nullptr;
    if (sweeps_suit < 0) sweeps_suit = SupernodalSolve::suits(supernodal(*L)) ? 1 : 0;
    if (sweeps_suit == 0) return nullptr;
    const int threads = thread_count();
    if (!sweeps || sweeps->threads() != threads) sweeps = std::make_unique<SupernodalSolve>(supernodal(*L), threads);
    return sweeps.get();
  }
  // to = P from (L's order) or from = Pᵀ to: a permutation, every entry written by one thread.
  void to_factor_order(const double* from, double* to) const {
    const int* perm = static_cast<const int*>(L->Perm);
    const int n = static_cast<int>(L->n);
#pragma omp parallel for schedule(static) if (n >= kParallelWork)
    for (int k = 0; k < n; ++k) to[k] = from[perm[k]];
  }
  void from_factor_order(const double* from, double* to) const {
    const int* perm = static_cast<const int*>(L->Perm);
    const int n = static_cast<int>(L->n);
#pragma omp parallel for schedule(static) if (n >= kParallelWork)
    for (int k = 0; k < n; ++k) to[perm[k]] = from[k];
  }
  void check_size(const Eigen::VectorXd& v, const char* what) const {
    if (v.size() != static_cast<long>(L->n))
      throw InputError(std::string("SparseCholesky: ") + what + " of a vector of " + std::to_string(v.size()) +
                       " entries with a factor of " + std::to_string(L->n));
  }
  // v ← L⁻¹ v or L⁻ᵀ v (sys: CHOLMOD_L or CHOLMOD_Lt) by CHOLMOD, v in L's order.
  void cholmod_half(int sys, Eigen::VectorXd& v) {
    cholmod_dense B;
    std::memset(&B, 0, sizeof B);
    B.nrow = B.nzmax = B.d = v.size();
    B.ncol = 1;
    B.x = v.data();
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    cholmod_solve2(sys, L, &B, nullptr, &X, nullptr, &Y, &E, &common);
    check("solve");
    v = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(X->x), v.size());
  }
  void check(const char* what) const {
    if (common.status < CHOLMOD_OK)
      throw NumericalError(std::string("CHOLMOD ") + what + " failed (status " + std::to_string(common.status) + ")");
  }
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const SparseMatrix& S) { analyze_with(S, nullptr); }

void SparseCholesky::analyze(const SparseMatrix& S, const std::vector<int>& ordering) {
  if (static_cast<long>(ordering.size()) != S.rows())
    throw InputError("SparseCholesky: an ordering of " + std::to_string(ordering.size()) + " unknowns for a matrix of " +
                     std::to_string(S.rows()));
  analyze_with(S, &ordering);
}

void SparseCholesky::analyze_with(const SparseMatrix& S, const std::vector<int>* ordering) {
  if (!S.isCompressed()) throw InputError("SparseCholesky: the matrix must be compressed");
  Impl& m = *impl_;
  m.free_factor(m.L);
  m.free_factor(m.kept);
  m.free_factor(m.symbolic);
  m.sweeps.reset();
  m.sweeps_suit = -1;
  m.paths.reset();
  cholmod_sparse A = Impl::view(S);
  if (ordering) {
    const int saved_nmethods = m.common.nmethods, saved_ordering = m.common.method[0].ordering;
    m.common.nmethods = 1;
    m.common.method[0].ordering = CHOLMOD_GIVEN;
    m.symbolic = cholmod_analyze_p(&A, const_cast<int*>(ordering->data()), nullptr, 0, &m.common);
    m.common.nmethods = saved_nmethods;
    m.common.method[0].ordering = saved_ordering;
  } else {
    m.symbolic = cholmod_analyze(&A, &m.common);
  }
  m.check("analyze");
  m.flops = m.common.fl;
  m.lnz = m.common.lnz;
  m.outer.assign(S.outerIndexPtr(), S.outerIndexPtr() + S.outerSize() + 1);
  m.inner.assign(S.innerIndexPtr(), S.innerIndexPtr() + S.nonZeros());
  const int n = static_cast<int>(S.rows());
  const int* perm = static_cast<const int*>(m.symbolic->Perm);
  m.position.assign(n, 0);
  for (int k = 0; k < n; ++k) m.position[perm[k]] = k;
}

std::vector<int> SparseCholesky::ordering() const {
  const Impl& m = *impl_;
  if (!m.symbolic) throw InputError("SparseCholesky: ordering() before analyze()");
  const int* perm = static_cast<const int*>(m.symbolic->Perm);
  return std::vector<int>(perm, perm + m.symbolic->n);
}

bool SparseCholesky::analyzed_for(const SparseMatrix& S) const {
  const Impl& m = *impl_;
  return m.symbolic && S.isCompressed() && static_cast<long>(m.outer.size()) == S.outerSize() + 1 &&
         static_cast<long>(m.inner.size()) == S.nonZeros() &&
         std::equal(m.outer.begin(), m.outer.end(), S.outerIndexPtr()) &&
         std::equal(m.inner.begin(), m.inner.end(), S.innerIndexPtr());
}

int SparseCholesky::factorize(const SparseMatrix& S) {
  Impl& m = *impl_;
  if (!analyzed_for(S)) throw InputError("SparseCholesky: factorize() with a pattern that was not analysed");
  m.free_factor(m.L);
  m.L = cholmod_copy_factor(m.symbolic, &m.common);
  m.check("copy_factor");
  cholmod_sparse A = Impl::view(S);
  within_thread_count([&] { cholmod_factorize(&A, m.L, &m.common); });
  if (m.common.status == CHOLMOD_NOT_POSDEF) {
    // L->minor is the column (in the permuted order) where the factorization stopped
    const int k = static_cast<int>(m.L->minor);
    const int* perm = static_cast<const int*>(m.symbolic->Perm);
    m.free_factor(m.L);
    return perm && k >= 0 && k < static_cast<int>(S.rows()) ? perm[k] : std::max(k, 0);
  }
  m.check("factorize");
  return -1;
}

bool SparseCholesky::factorized() const { return impl_->L != nullptr; }

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
  Impl& m = *impl_;
  if (!m.L) throw InputError("SparseCholesky: solve() without a factor (factorize() first, or it failed)");
  if (const SupernodalSolve* sweeps = m.subtree_sweeps()) {
    // Our sweeps by subtrees, on the kernel's threads (CHOLMOD's are one sweep).
    m.check_size(b, "solve()");
    m.y.resize(b.size());
    m.to_factor_order(b.data(), m.y.data());
    sweeps->solve(Impl::supernodal(*m.L), m.y.data());
    Eigen::VectorXd x(b.size());
    m.from_factor_order(m.y.data(), x.data());
    return x;
  }
  cholmod_dense B;
  std::memset(&B, 0, sizeof B);
  B.nrow = b.size();
  B.ncol = 1;
  B.nzmax = b.size();
  B.d = b.size();
  B.x = const_cast<double*>(b.data());
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  cholmod_solve2(CHOLMOD_A, m.L, &B, nullptr, &m.X, nullptr, &m.Y, &m.E, &m.common);
  m.check("solve");
  return Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(m.X->x), b.size());
}

bool SparseCholesky::has_halves() const { return impl_->L && impl_->L->is_ll; }

void SparseCholesky::forward(Eigen::VectorXd& v) const {
  Impl& m = *impl_;
  if (!has_halves()) throw InputError("SparseCholesky: forward() needs an LLᵀ factor");
  m.check_size(v, "forward()");
  m.y.resize(v.size());
  m.to_factor_order(v.data(), m.y.data());
  v.swap(m.y);
  if (const SupernodalSolve* sweeps = m.subtree_sweeps())
    sweeps->forward(Impl::supernodal(*m.L), v.data());
  else
    m.cholmod_half(CHOLMOD_L, v);
}

void SparseCholesky::backward(Eigen::VectorXd& v) const {
  Impl& m = *impl_;
  if (!has_halves()) throw InputError("SparseCholesky: backward() needs an LLᵀ factor");
  m.check_size(v, "backward()");
  if (const SupernodalSolve* sweeps = m.subtree_sweeps())
    sweeps->backward(Impl::supernodal(*m.L), v.data());
  else
    m.cholmod_half(CHOLMOD_Lt, v);
  m.y.resize(v.size());
  m.from_factor_order(v.data(), m.y.data());
  v.swap(m.y);
}

double SparseCholesky::unit_forward(int i, std::vector<int>& rows, std::vector<double>& values) const {
  Impl& m = *impl_;
  if (!has_halves()) throw InputError("SparseCholesky: unit_forward() needs an LLᵀ factor");
  const int k = m.position[i];
  if (m.L->is_super) {
    if (!m.paths) m.paths = std::make_unique<SupernodalPaths>(Impl::supernodal(*m.L));
    return m.paths->unit_forward(Impl::supernodal(*m.L), k, rows, values);
  }
  // Simplicial: column j's entries at Lp[j] … Lp[j] + Lnz[j] − 1, its diagonal first, its
  // parent in the tree its first row below (CHOLMOD keeps the rows sorted).
  const int* Lp = static_cast<const int*>(m.L->p);
  const int* Li = static_cast<const int*>(m.L->i);
  const int* Lnz = static_cast<const int*>(m.L->nz);
  const double* Lx = static_cast<const double*>(m.L->x);
  m.z.resize(m.L->n, 0.0);
  rows.clear();
  values.clear();
  double flops = 0.0;
  m.z[k] = 1.0;
  for (int j = k; j >= 0;) {
    const int p0 = Lp[j], p1 = Lp[j] + Lnz[j];
    const double zj = m.z[j] / Lx[p0];
    for (int p = p0 + 1; p < p1; ++p) m.z[Li[p]] -= Lx[p] * zj;
    flops += 2.0 * (p1 - p0);
    rows.push_back(j);
    values.push_back(zj);
    m.z[j] = 0.0;
    j = p1 > p0 + 1 ? Li[p0 + 1] : -1;
  }
  return flops;
}

void SparseCholesky::keep() {
  Impl& m = *impl_;
  if (!m.L) throw InputError("SparseCholesky: keep() without a factor");
  m.copy_factor(m.L, m.kept);
}

bool SparseCholesky::has_kept() const { return impl_->kept != nullptr; }

void SparseCholesky::use_kept() {
  Impl& m = *impl_;
  if (!m.kept) throw InputError("SparseCholesky: use_kept() without a kept factor");
  m.copy_factor(m.kept, m.L);
}

void SparseCholesky::forget_kept() { impl_->free_factor(impl_->kept); }

void SparseCholesky::replace_by_identity(int i) {
  Impl& m = *impl_;
  cholmod_rowdel(m.position[i], nullptr, m.L, &m.common);
  m.check("rowdel");
}

double SparseCholesky::modification_flops() const { return impl_->common.modfl; }

double SparseCholesky::factorization_flops() const { return impl_->flops; }

double SparseCholesky::solve_flops() const { return 4.0 * impl_->lnz; }

bool SparseCholesky::restore(int i, const SparseMatrix& S, const std::vector<char>& keep) {
  Impl& m = *impl_;
  const int n = static_cast<int>(S.rows());
  int count = 0;
  for (SparseMatrix::InnerIterator it(S, i); it; ++it) count += keep[it.row()] ? 1 : 0;
  cholmod_sparse* R = cholmod_allocate_sparse(n, 1, count, /*sorted=*/0, /*packed=*/1, /*stype=*/0,
                                              CHOLMOD_REAL, &m.common);
  m.check("allocate_sparse");
  int* Rp = static_cast<int*>(R->p);
  int* Ri = static_cast<int*>(R->i);
  double* Rx = static_cast<double*>(R->x);
  Rp[0] = 0;
  int p = 0;
  // column i of P S Pᵀ: entry (position[row], position[i]) = S(row, i)
  for (SparseMatrix::InnerIterator it(S, i); it; ++it)
    if (keep[it.row()]) {
      Ri[p] = m.position[it.row()];
      Rx[p] = it.value();
      ++p;
    }
  Rp[1] = p;
  cholmod_rowadd(m.position[i], R, m.L, &m.common);
  cholmod_free_sparse(&R, &m.common);
  if (m.common.status == CHOLMOD_NOT_POSDEF) return false;
  m.check("rowadd");
  return true;
}

void check_positive_definite(const SparseMatrix& S, const std::string& what) {
  SparseCholesky chol;
  chol.analyze(S);
  const int minor = chol.factorize(S);
  if (minor >= 0)
    throw NumericalError(what + " is not positive definite (CHOLMOD: the factorization breaks down at column " +
                         std::to_string(minor) + ")");
}

}  // namespace cdyn
