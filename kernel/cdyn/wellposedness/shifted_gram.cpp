// shifted_gram.cpp — M(σ) = K Kᵀ − σ E assembled once, shifted in place, factorized by
// CHOLMOD (through Eigen's CholmodSupport: the pattern is analysed once).
#include "cdyn/wellposedness/shifted_gram.hpp"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/threads.hpp"

namespace cdyn {

namespace {

// Eigen's supernodal LLᵀ, with the factor's diagonal made visible for rcond() and
// CHOLMOD's messages silenced: a matrix that is not positive definite is an answer here.
class SupernodalCholesky : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  SupernodalCholesky() { cholmod().print = 0; }
  double rcond() { return m_cholmodFactor ? cholmod_rcond(m_cholmodFactor, &cholmod()) : 0.0; }
  int status() { return cholmod().status; }
};

}  // namespace

struct ShiftedGram::Impl {
  int n_H = 0, n_g = 0;
  SparseMatrix K;                  // [B; G], (N_H + N_g) × N_W
  SparseMatrix M;                  // lower triangle of K Kᵀ − σ E
  Eigen::VectorXd gram_diagonal;   // (G Gᵀ)_ii
  std::vector<int> shifted;        // positions in M's values of the diagonal of the G block
  SupernodalCholesky chol;
  int factorizations = 0;
  mutable int solves = 0;
};

ShiftedGram::ShiftedGram(const SparseMatrix& B, const SparseMatrix& G) : impl_(std::make_unique<Impl>()) {
  if (B.cols() != G.cols()) throw InputError("ShiftedGram: B and G have different numbers of columns");
  Impl& m = *impl_;
  m.n_H = static_cast<int>(B.rows());
  m.n_g = static_cast<int>(G.rows());
  const int n = m.n_H + m.n_g;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(B.nonZeros() + G.nonZeros());
  for (int j = 0; j < B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (int j = 0; j < G.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(G, j); it; ++it) t.emplace_back(m.n_H + it.row(), j, it.value());
  m.K.resize(n, B.cols());
  m.K.setFromTriplets(t.begin(), t.end());
  // The G block's diagonal is stored explicitly (a zero row of G would leave it out of
  // the pattern), so that every shift has a place to go: D holds explicit zeros there,
  // and a sparse sum keeps the union of the patterns.
  SparseMatrix D(n, n);
  std::vector<Eigen::Triplet<double>> d;
  for (int i = m.n_H; i < n; ++i) d.emplace_back(i, i, 0.0);
  D.setFromTriplets(d.begin(), d.end());
  const SparseMatrix KKt = m.K * m.K.transpose();
  m.M = SparseMatrix(KKt.triangularView<Eigen::Lower>()) + D;
  m.M.makeCompressed();
  m.gram_diagonal.resize(m.n_g);
  m.shifted.resize(m.n_g);
  for (int i = m.n_H; i < n; ++i) {
    const int* begin = m.M.innerIndexPtr() + m.M.outerIndexPtr()[i];
    const int* end = m.M.innerIndexPtr() + m.M.outerIndexPtr()[i + 1];
    const int* d = std::lower_bound(begin, end, i);
    if (d == end || *d != i) throw NumericalError("ShiftedGram: the diagonal of the G block is not stored");
    m.shifted[i - m.n_H] = static_cast<int>(d - m.M.innerIndexPtr());
    m.gram_diagonal[i - m.n_H] = m.M.valuePtr()[m.shifted[i - m.n_H]];
  }
  m.chol.analyzePattern(m.M);
  if (m.chol.info() != Eigen::Success)
    throw NumericalError("condition (12): CHOLMOD could not analyse the Gram matrix of [B; G] (status " +
                         std::to_string(m.chol.status()) + ")");
}

ShiftedGram::~ShiftedGram() = default;

bool ShiftedGram::factorize(double sigma) {
  Impl& m = *impl_;
  for (int i = 0; i < m.n_g; ++i) m.M.valuePtr()[m.shifted[i]] = m.gram_diagonal[i] - sigma;
  ++m.factorizations;
  within_thread_count([&] { m.chol.factorize(m.M); });
  if (m.chol.info() == Eigen::Success) return true;
  if (m.chol.status() == CHOLMOD_NOT_POSDEF) return false;
  throw NumericalError("condition (12): CHOLMOD could not factorize the Gram matrix of [B; G] (status " +
                       std::to_string(m.chol.status()) + (m.chol.status() == CHOLMOD_OUT_OF_MEMORY ? ", out of memory" : "") +
                       ")");
}

double ShiftedGram::rcond() const { return impl_->chol.rcond(); }

Eigen::VectorXd ShiftedGram::solve(const Eigen::VectorXd& q, Eigen::VectorXd* W) const {
  const Impl& m = *impl_;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m.n_H + m.n_g);
  rhs.tail(m.n_g) = q;
  const Eigen::VectorXd x = m.chol.solve(rhs);
  ++m.solves;
  if (W) *W = m.K.transpose() * x;
  return x.tail(m.n_g);
}

int ShiftedGram::factorizations() const { return impl_->factorizations; }
int ShiftedGram::solves() const { return impl_->solves; }

}  // namespace cdyn
