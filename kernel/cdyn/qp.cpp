// qp.cpp — the step QP: input checks, the common KKT measure, X ↦ S X in either form,
// the CHOLMOD factorization shared by the solvers, and the solver factory.
#include "cdyn/qp.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "cdyn/error.hpp"
#include "cdyn/qp_ipopt.hpp"
#include "cdyn/qp_nlopt.hpp"
#include "cdyn/qp_pdas.hpp"
#include "cdyn/qp_pgs.hpp"

namespace cdyn {

namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

void check_finite(const SparseMatrix& M, const std::string& what) {
  for (int j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it)
      if (!std::isfinite(it.value()))
        throw InputError("BoundQP: " + what + "(" + std::to_string(it.row()) + "," +
                         std::to_string(j) + ") = " + num(it.value()) + " is not finite");
}

void check_symmetric(const SparseMatrix& M, const std::string& what) {
  const SparseMatrix T = M.transpose();
  double max_entry = 0.0;
  for (int j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) max_entry = std::max(max_entry, std::abs(it.value()));
  const SparseMatrix diff = M - T;
  for (int j = 0; j < diff.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(diff, j); it; ++it)
      if (std::abs(it.value()) > 1e-10 * max_entry)
        throw InputError("BoundQP: " + what + " is not symmetric: entry (" + std::to_string(it.row()) + "," +
                         std::to_string(j) + ") differs from its transpose by " + num(it.value()));
}

}  // namespace

// ----- input checks ----------------------------------------------------------------------

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
    if (!(std::isfinite(f.c) && f.c > 0)) throw InputError("BoundQP: saddle factor c = " + num(f.c) + " must be > 0");
    if (matrices) {
      check_finite(f.A, "A");
      check_finite(f.B, "B");
      check_finite(f.C, "C");
      check_symmetric(f.A, "A");
      check_symmetric(f.C, "C");
    }
  }
  // (called every step: the index text is made only for a message, not per unknown)
  auto at = [](int i) { return "[" + std::to_string(i) + "]"; };
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(qp.r[i])) throw InputError("BoundQP: r" + at(i) + " = " + num(qp.r[i]) + " is not finite");
    if (std::isnan(qp.lower[i]) || std::isnan(qp.upper[i])) throw InputError("BoundQP: bound" + at(i) + " is NaN");
    if (qp.lower[i] == std::numeric_limits<double>::infinity() ||
        qp.upper[i] == -std::numeric_limits<double>::infinity())
      throw InputError("BoundQP: bounds" + at(i) + " exclude every finite value: the constraint set is empty");
    if (qp.lower[i] > qp.upper[i])
      throw InputError("BoundQP: lower" + at(i) + " = " + num(qp.lower[i]) + " > upper" + at(i) + " = " +
                       num(qp.upper[i]) + ": the constraint set is empty");
  }
}

bool CheckedMatrices::check(const BoundQP& qp, bool positive_definite, const std::string& solver) {
  bool same = valid_;
  if (same && qp.saddle)
    same = S_.size() == 0 && qp.saddle->c == c_ && same_matrix(qp.saddle->A, A_) && same_matrix(qp.saddle->B, B_) &&
           same_matrix(qp.saddle->C, C_);
  else if (same)
    same = A_.size() == 0 && same_matrix(qp.S, S_);
  check_problem(qp, !same);
  if (same) return false;
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
  return true;
}

// ----- the common KKT measure ------------------------------------------------------------

Eigen::VectorXd scaling_diagonal(const BoundQP& qp) {
  if (!qp.saddle) return qp.S.diagonal();
  const SaddleForm& f = *qp.saddle;
  Eigen::VectorXd D = f.A.diagonal();
  const Eigen::VectorXd Cd = f.C.diagonal();
  for (int j = 0; j < f.B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(f.B, j); it; ++it) D[j] += f.c * it.value() * it.value() / Cd[it.row()];
  return D;
}

Eigen::VectorXd natural_residual(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                                 const Eigen::VectorXd& D) {
  const int n = qp.size();
  Eigen::VectorXd F(n);
  for (int i = 0; i < n; ++i) {
    const double step = X[i] - reaction[i] / D[i];
    F[i] = X[i] - std::clamp(step, qp.lower[i], qp.upper[i]);
  }
  return F;
}

double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                    const Eigen::VectorXd* D_known) {
  if (qp.size() == 0) return 0.0;
  const Eigen::VectorXd D = D_known ? *D_known : scaling_diagonal(qp);
  const double F = natural_residual(qp, X, reaction, D).lpNorm<Eigen::Infinity>();
  const double scale = std::max(X.lpNorm<Eigen::Infinity>(), qp.r.cwiseQuotient(D).lpNorm<Eigen::Infinity>());
  if (!std::isfinite(F)) return std::numeric_limits<double>::infinity();
  return scale > 0 ? F / scale : F;
}

double kkt_residual(const BoundQP& qp, const Eigen::VectorXd& X) {
  QuadraticForm form;
  form.set(qp);
  return kkt_residual(qp, X, form.apply(X) - qp.r);
}

std::vector<int> active_set(const BoundQP& qp, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                            const Eigen::VectorXd& D) {
  std::vector<int> active;
  for (int i = 0; i < qp.size(); ++i) {
    const double l = qp.lower[i], u = qp.upper[i];
    if (l == u || (std::isfinite(l) && reaction[i] > D[i] * (X[i] - l)) ||
        (std::isfinite(u) && reaction[i] < D[i] * (X[i] - u)))
      active.push_back(i);
  }
  return active;
}

void finish_result(const BoundQP& qp, const QuadraticForm& form, double tol, QPResult& result) {
  result.reaction = form.apply(result.X) - qp.r;
  const Eigen::VectorXd& D = form.diagonal();
  result.kkt_residual = kkt_residual(qp, result.X, result.reaction, &D);
  result.active = active_set(qp, result.X, result.reaction, D);
  result.converged = result.kkt_residual <= tol;
}

void report_failure(const std::string& solver, const QPOptions& options, const QPResult& result,
                    const std::string& detail) {
  if (result.converged || !options.throw_on_failure) return;
  throw NumericalError(solver + ": did not converge: KKT residual " + num(result.kkt_residual) + " > tol " +
                       num(options.tol) + " after " + std::to_string(result.iterations) + " iterations" +
                       (detail.empty() ? "" : " (" + detail + ")"));
}

bool same_matrix(const SparseMatrix& a, const SparseMatrix& b, bool values) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  if (!a.isCompressed() || !b.isCompressed()) return false;
  const auto nnz = static_cast<std::size_t>(a.nonZeros());
  if (nnz == 0) return true;  // (memcmp must not see the null arrays of an empty matrix)
  if (std::memcmp(a.outerIndexPtr(), b.outerIndexPtr(), sizeof(int) * (a.outerSize() + 1)) != 0) return false;
  if (std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * nnz) != 0) return false;
  return !values || std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * nnz) == 0;
}

void check_positive_definite(const SparseMatrix& S, const std::string& what) {
  SparseCholesky chol;
  chol.analyze(S);
  const int minor = chol.factorize(S);
  if (minor >= 0)
    throw NumericalError(what + " is not positive definite (CHOLMOD: the factorization breaks down at column " +
                         std::to_string(minor) + ")");
}

// ----- X ↦ S X ------------------------------------------------------------------------------

QuadraticForm::QuadraticForm() = default;
QuadraticForm::~QuadraticForm() = default;

void QuadraticForm::set(const BoundQP& qp, bool same_matrices) {
  const bool keep = same_matrices && qp_ != nullptr && D_.size() == qp.size();
  qp_ = &qp;
  if (keep) return;  // (a pass over S saved per step: the time loop's matrices do not change)
  D_ = scaling_diagonal(qp);
  if (!qp.saddle) return;
  const SparseMatrix& C = qp.saddle->C;
  if (c_factor_ && same_matrix(C, C_)) return;
  C_ = C;
  C_.makeCompressed();
  c_factor_ = std::make_unique<SparseCholesky>();
  c_factor_->analyze(C_);
  const int minor = c_factor_->factorize(C_);
  if (minor >= 0) {
    c_factor_.reset();
    throw NumericalError("saddle block C is not positive definite (CHOLMOD: breakdown at column " +
                         std::to_string(minor) + ")");
  }
}

Eigen::VectorXd QuadraticForm::apply(const Eigen::VectorXd& X) const {
  if (!qp_->saddle) return qp_->S * X;
  const SaddleForm& f = *qp_->saddle;
  const Eigen::VectorXd Z = c_factor_->solve(f.B * X);  // Z = C⁻¹ B X
  return f.A * X + f.c * (f.B.transpose() * Z);
}

double QuadraticForm::objective(const Eigen::VectorXd& X) const {
  return 0.5 * X.dot(apply(X)) - qp_->r.dot(X);
}

// ----- CHOLMOD -------------------------------------------------------------------------------

struct SparseCholesky::Impl {
  cholmod_common common;
  cholmod_factor* symbolic = nullptr;  // the analysis, kept to start each factorization from
  cholmod_factor* L = nullptr;         // the current numeric factor
  std::vector<int> outer, inner;       // pattern of the analysed matrix
  std::vector<int> position;           // position[i] = row of L holding original unknown i
  mutable cholmod_dense* X = nullptr;  // solve workspaces (cholmod_solve2)
  mutable cholmod_dense* Y = nullptr;
  mutable cholmod_dense* E = nullptr;

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
  void check(const char* what) const {
    if (common.status < CHOLMOD_OK)
      throw NumericalError(std::string("CHOLMOD ") + what + " failed (status " + std::to_string(common.status) + ")");
  }
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const SparseMatrix& S) {
  if (!S.isCompressed()) throw InputError("SparseCholesky: the matrix must be compressed");
  Impl& m = *impl_;
  m.free_factor(m.L);
  m.free_factor(m.symbolic);
  cholmod_sparse A = Impl::view(S);
  m.symbolic = cholmod_analyze(&A, &m.common);
  m.check("analyze");
  m.outer.assign(S.outerIndexPtr(), S.outerIndexPtr() + S.outerSize() + 1);
  m.inner.assign(S.innerIndexPtr(), S.innerIndexPtr() + S.nonZeros());
  const int n = static_cast<int>(S.rows());
  const int* perm = static_cast<const int*>(m.symbolic->Perm);
  m.position.assign(n, 0);
  for (int k = 0; k < n; ++k) m.position[perm[k]] = k;
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
  cholmod_factorize(&A, m.L, &m.common);
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

void SparseCholesky::replace_by_identity(int i) {
  Impl& m = *impl_;
  cholmod_rowdel(m.position[i], nullptr, m.L, &m.common);
  m.check("rowdel");
}

double SparseCholesky::modification_flops() const { return impl_->common.modfl; }

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

// ----- the factory ---------------------------------------------------------------------------

std::vector<std::string> step_solver_names() { return {"pdas", "pgs", "ipopt", "nlopt"}; }

std::unique_ptr<StepSolver> make_step_solver(const std::string& name, const QPOptions& options) {
  if (!(options.tol > 0) || !std::isfinite(options.tol))
    throw InputError("solver.tol = " + num(options.tol) + " must be a positive number");
  if (options.max_iterations < 0)
    throw InputError("solver.max_iterations = " + std::to_string(options.max_iterations) + " must be >= 0");
  if (name == "pdas") return std::make_unique<PDASSolver>(options);
  if (name == "pgs") return std::make_unique<PGSSolver>(options);
  if (name == "ipopt") return std::make_unique<IpoptSolver>(options);
  if (name == "nlopt") return std::make_unique<NLoptSolver>(options);
  throw InputError("solver.name = '" + name + "' is not a step solver (known: pdas, pgs, ipopt, nlopt)");
}

}  // namespace cdyn
