// grid_fixtures.hpp — a 2D mesh's kind of SPD matrix for the linear algebra's tests: the
// 5-point stencil on a k × k grid (Dirichlet outside) with `diagonal` on the diagonal
// and −1 for each neighbour, i.e. the Laplacian plus (diagonal − 4) I; its eigenvalues
// lie in (diagonal − 4, diagonal + 4), SPD for diagonal ≥ 4.  Unknown i·k + j is the
// grid point (i, j).
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "cdyn/base/sparse.hpp"

inline cdyn::SparseMatrix grid_laplacian(int k, double diagonal) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const int p = i * k + j;
      t.emplace_back(p, p, diagonal);
      if (i + 1 < k) t.emplace_back(p, p + k, -1.0), t.emplace_back(p + k, p, -1.0);
      if (j + 1 < k) t.emplace_back(p, p + 1, -1.0), t.emplace_back(p + 1, p, -1.0);
    }
  cdyn::SparseMatrix S(k * k, k * k);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}
