// linalg/parallel.cpp — gathers over compressed columns and sums by blocks; see
// linalg/parallel.hpp.
#include "cdyn/linalg/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/prefetch.hpp"

namespace cdyn {

void transpose_times(const SparseMatrix& M, const double* x, double* y) {
  const int n = static_cast<int>(M.cols());
  const int* outer = M.outerIndexPtr();
  const int* count = M.innerNonZeroPtr();  // null when compressed
  const int* inner = M.innerIndexPtr();
  const double* v = M.valuePtr();
#pragma omp parallel for schedule(static) if (M.nonZeros() >= kParallelWork)
  for (int i = 0; i < n; ++i) {
    const int end = count ? outer[i] + count[i] : outer[i + 1];
    // 256 entries ahead, two lines of values and one of indices a column (a column has
    // about a dozen): at n = 640, where such products are a fifth of the free step, 5 %
    // off the step (linalg/prefetch.hpp)
    prefetch_line(v, outer[i] + 256);
    prefetch_line(v, outer[i] + 256 + 8);
    prefetch_line(inner, outer[i] + 256);
    double sum = 0.0;
    for (int k = outer[i]; k < end; ++k) sum += v[k] * x[inner[k]];
    y[i] = sum;
  }
}

Eigen::VectorXd transpose_times(const SparseMatrix& M, const Eigen::VectorXd& x) {
  if (x.size() != M.rows())
    throw InputError("transpose_times: a vector of " + std::to_string(x.size()) + " entries for a matrix of " +
                     std::to_string(M.rows()) + " rows");
  Eigen::VectorXd y(M.cols());
  transpose_times(M, x.data(), y.data());
  return y;
}

Eigen::VectorXd symmetric_times(const SparseMatrix& S, const Eigen::VectorXd& x) {
  if (S.rows() != S.cols()) throw InputError("symmetric_times: the matrix is not square");
  return transpose_times(S, x);
}

double dot(long n, const double* x, const double* y) {
  using Block = Eigen::Map<const Eigen::VectorXd>;
  const int blocks = block_count(n);
  std::vector<double> sums(blocks);
#pragma omp parallel for schedule(static) if (n >= kParallelWork)
  for (int b = 0; b < blocks; ++b) {
    const long begin = long(b) * kBlock, length = std::min<long>(kBlock, n - begin);
    sums[b] = Block(x + begin, length).dot(Block(y + begin, length));
  }
  double sum = 0.0;
  for (double s : sums) sum += s;
  return sum;
}

void for_each_block(long n, const std::function<void(long, long)>& f) {
  const int blocks = block_count(n);
#pragma omp parallel for schedule(static) if (n >= kParallelWork)
  for (int b = 0; b < blocks; ++b) f(long(b) * kBlock, std::min<long>(n, long(b + 1) * kBlock));
}

double max_abs(const Eigen::VectorXd& x, const Eigen::VectorXd* scale) {
  const long n = x.size();
  if (scale && scale->size() != n)
    throw InputError("max_abs: a scale of " + std::to_string(scale->size()) + " entries for " + std::to_string(n));
  // (a NaN is flagged apart, so that the maximum is a plain one, which vectorizes)
  const double* v = x.data();
  const double* s = scale ? scale->data() : nullptr;
  double m = 0.0;
  int nan = 0;
  if (s) {
#pragma omp parallel for simd schedule(static) reduction(max : m) reduction(| : nan) if (2 * n >= kParallelWork)
    for (long i = 0; i < n; ++i) {
      const double a = std::abs(v[i]) / s[i];
      nan |= a != a;
      m = a > m ? a : m;
    }
  } else {
#pragma omp parallel for simd schedule(static) reduction(max : m) reduction(| : nan) if (2 * n >= kParallelWork)
    for (long i = 0; i < n; ++i) {
      const double a = std::abs(v[i]);
      nan |= a != a;
      m = a > m ? a : m;
    }
  }
  return nan ? std::numeric_limits<double>::quiet_NaN() : m;
}

double dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  if (x.size() != y.size())
    throw InputError("dot: vectors of " + std::to_string(x.size()) + " and " + std::to_string(y.size()) + " entries");
  return dot(x.size(), x.data(), y.data());
}

SparseMatrix transposed(const SparseMatrix& M) {
  SparseMatrix T = M.transpose();
  T.makeCompressed();
  return T;
}

}  // namespace cdyn
