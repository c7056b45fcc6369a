// massless_modes.cpp — a local basis of Ker B: zero columns and private columns.
#include "cdyn/mass/massless_modes.hpp"

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/least_squares.hpp"

namespace cdyn {

std::optional<MasslessModes> massless_modes(const SparseMatrix& B_in, const std::vector<char>& bounded) {
  SparseMatrix B = B_in;
  B.prune(0.0);  // exact zeros do not couple
  B.makeCompressed();
  const int n = static_cast<int>(B.cols()), rows = static_cast<int>(B.rows());
  if (static_cast<int>(bounded.size()) != n) throw InputError("massless_modes: one bound flag per column expected");
  const int* outer = B.outerIndexPtr();
  auto nnz = [&](int j) { return outer[j + 1] - outer[j]; };

  // Zero columns are massless by themselves.
  std::vector<int> zero, rest;
  for (int j = 0; j < n; ++j) (nnz(j) == 0 ? zero : rest).push_back(j);
  std::vector<Eigen::Triplet<double>> t;
  MasslessModes modes;
  for (int j : zero) {
    t.emplace_back(j, static_cast<int>(modes.pinned.size()), 1.0);
    modes.pinned.push_back(j);
  }

  // Private columns: one unbounded unknown per row that no other row sees — the last of
  // them, which for P1+ is the cell's bubble (numbered after the vertices), also where a
  // vertex lies in that one cell only: a corner of the mesh, or of a subdomain's
  // sub-mesh (mesh/sub_mesh.hpp), whose basis must be the restriction of the whole's.
  std::vector<int> private_of(rows, -1);
  std::vector<char> is_private(n, 0);
  for (int j : rest)
    if (nnz(j) == 1 && !bounded[j]) private_of[B.innerIndexPtr()[outer[j]]] = j;
  for (int j : private_of)
    if (j >= 0) is_private[j] = 1;
  bool every_row = rows > 0;
  for (int r = 0; r < rows && every_row; ++r) every_row = private_of[r] >= 0;

  if (!every_row) {
    // No elimination: the remaining columns must carry no kernel.
    if (!rest.empty()) {
      SparseMatrix Br(rows, static_cast<int>(rest.size()));
      std::vector<Eigen::Triplet<double>> tr;
      for (int k = 0; k < static_cast<int>(rest.size()); ++k)
        for (SparseMatrix::InnerIterator it(B, rest[k]); it; ++it) tr.emplace_back(it.row(), k, it.value());
      Br.setFromTriplets(tr.begin(), tr.end());
      if (!full_column_rank(Br)) return std::nullopt;
    }
  } else {
    for (int j : rest) {
      if (is_private[j]) continue;
      const int k = static_cast<int>(modes.pinned.size());
      t.emplace_back(j, k, 1.0);
      for (SparseMatrix::InnerIterator it(B, j); it; ++it) {
        const int p = private_of[it.row()];
        const double Bp = B.coeff(it.row(), p);
        t.emplace_back(p, k, -it.value() / Bp);
      }
      modes.pinned.push_back(j);
    }
  }
  modes.Z.resize(n, static_cast<int>(modes.pinned.size()));
  modes.Z.setFromTriplets(t.begin(), t.end());
  modes.Z.makeCompressed();
  return modes;
}

}  // namespace cdyn
