// sparse.cpp — comparing two compressed sparse matrices.
#include "cdyn/base/sparse.hpp"

#include <cstring>

namespace cdyn {

bool same_matrix(const SparseMatrix& a, const SparseMatrix& b, bool values) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  if (!a.isCompressed() || !b.isCompressed()) return false;
  const auto nnz = static_cast<std::size_t>(a.nonZeros());
  if (nnz == 0) return true;  // (memcmp must not see the null arrays of an empty matrix)
  if (std::memcmp(a.outerIndexPtr(), b.outerIndexPtr(), sizeof(int) * (a.outerSize() + 1)) != 0) return false;
  if (std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * nnz) != 0) return false;
  return !values || std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * nnz) == 0;
}

}  // namespace cdyn
