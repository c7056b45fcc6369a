// wellposedness_fixtures.hpp — small helpers the condition (12) tests share
// (test_wellposedness.cpp, test_wellposedness_sparse.cpp): hand matrices, mesh parts by
// name, every vertex as a constraint, the seed's membrane setup.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "cdyn/base/sparse.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/wellposedness/condition12.hpp"

namespace cdyn::testing {

inline SparseMatrix sparse(const Eigen::MatrixXd& D) { return D.sparseView(); }

inline std::vector<int> parts(const Mesh& m, const std::vector<std::string>& names) {
  std::vector<int> p;
  for (const auto& n : names) p.push_back(m.part_index(n));
  return p;
}

inline std::vector<int> all_vertices(const Mesh& m) {
  std::vector<int> v(m.n_vertices());
  for (int i = 0; i < m.n_vertices(); ++i) v[i] = i;
  return v;
}

// The seed's membrane setup: u fixed on the whole boundary of the unit square, the
// obstacle u(a_i) ≥ g at every (free) vertex.
inline WellPosednessSetup clamped_membrane_setup(const Mesh& m) {
  WellPosednessSetup setup;
  setup.dirichlet_parts = parts(m, {"bottom", "right", "top", "left"});
  setup.constrained_vertices = all_vertices(m);
  return setup;
}

}  // namespace cdyn::testing
