// sparse.cpp — comparing two compressed sparse matrices; the symmetric saddle matrix.
#include "cdyn/base/sparse.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

namespace cdyn {

namespace {

// memcmp(a, b, bytes) == 0, by blocks of 64 KiB shared among the threads: the solvers
// compare S with the last one at every step, a pass over its values that costs as much as
// a product with it.  (A yes-or-no answer: the same on any number of threads.)
bool same_bytes(const void* a, const void* b, std::size_t bytes) {
  constexpr std::size_t kBlockBytes = std::size_t(1) << 16;
  const auto* x = static_cast<const unsigned char*>(a);
  const auto* y = static_cast<const unsigned char*>(b);
  const long blocks = static_cast<long>((bytes + kBlockBytes - 1) / kBlockBytes);
  bool same = true;
#pragma omp parallel for schedule(static) reduction(&& : same) if (blocks >= 4)
  for (long k = 0; k < blocks; ++k) {
    const std::size_t begin = k * kBlockBytes, length = std::min(kBlockBytes, bytes - begin);
    same = same && std::memcmp(x + begin, y + begin, length) == 0;
  }
  return same;
}

}  // namespace

bool same_matrix(const SparseMatrix& a, const SparseMatrix& b, bool values) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  if (!a.isCompressed() || !b.isCompressed()) return false;
  const auto nnz = static_cast<std::size_t>(a.nonZeros());
  if (nnz == 0) return true;  // (memcmp must not see the null arrays of an empty matrix)
  if (!same_bytes(a.outerIndexPtr(), b.outerIndexPtr(), sizeof(int) * (a.outerSize() + 1))) return false;
  if (!same_bytes(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * nnz)) return false;
  return !values || same_bytes(a.valuePtr(), b.valuePtr(), sizeof(double) * nnz);
}

SparseMatrix symmetric_saddle_matrix(const SaddleForm& f) {
  const int n = static_cast<int>(f.A.cols()), m = static_cast<int>(f.C.rows());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(f.A.nonZeros() + 2 * f.B.nonZeros() + f.C.nonZeros() + n);
  for (int j = 0; j < n; ++j) t.emplace_back(j, j, 0.0);  // a stored diagonal for the identity rows
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(f.A, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(f.B, j); it; ++it) {
      t.emplace_back(n + it.row(), j, f.c * it.value());  // c B
      t.emplace_back(j, n + it.row(), f.c * it.value());  // c Bᵀ
    }
  for (int j = 0; j < m; ++j)
    for (SparseMatrix::InnerIterator it(f.C, j); it; ++it) t.emplace_back(n + it.row(), n + j, -f.c * it.value());
  SparseMatrix K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  return K;
}

}  // namespace cdyn
