// mass_fixtures.hpp — helpers the mass-model tests share (test_mass_model.cpp,
// test_mass_model_3d.cpp): a mass model as a dense matrix, the contact dofs of named
// parts, the interpolated affine fields.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "cdyn/mass/mass_model.hpp"

namespace cdyn::testing {

// M as a dense matrix: matrix() when the model has it, else column by column through
// the operators the time schemes use, M e_j = Bᵀ (C⁻¹ B e_j) (dense only in tests).
inline Eigen::MatrixXd dense_mass(const MassModel& m, int n) {
  if (const auto M = m.matrix()) return Eigen::MatrixXd(*M);
  Eigen::MatrixXd D(n, n);
  for (int j = 0; j < n; ++j) D.col(j) = m.momentum(m.velocity(Eigen::VectorXd::Unit(n, j)));
  return D;
}

// The free dofs (all components, or `components`) of the vertices of the named parts:
// the contact dofs.
inline std::vector<int> contact_dofs(const FESpace& W, const DirichletLift& bc, const std::vector<std::string>& names,
                                     std::vector<int> components = {}) {
  if (components.empty())
    for (int k = 0; k < W.components(); ++k) components.push_back(k);
  std::vector<int> part_indices, c;
  for (const auto& name : names) part_indices.push_back(W.mesh().part_index(name));
  for (int v : W.mesh().part_vertices(part_indices))
    for (int k : components)
      if (const int f = bc.free_index(W.vertex_dof(v, k)); f >= 0) c.push_back(f);
  return c;
}

// The interpolated affine fields restricted to the free dofs: 1, x, y, z per component
// (the first dim + 1 of them).  Column order: component-major.
inline Eigen::MatrixXd affine_fields(const FESpace& W, const DirichletLift& bc) {
  const std::vector<Field> f = {[](const Point&, double) { return 1.0; }, [](const Point& p, double) { return p.x; },
                                [](const Point& p, double) { return p.y; }, [](const Point& p, double) { return p.z; }};
  const int nf = W.dim() + 1, nc = W.components();
  Eigen::MatrixXd P(bc.n_free(), nf * nc);
  const Field zero = [](const Point&, double) { return 0.0; };
  for (int k = 0; k < nc; ++k)
    for (int a = 0; a < nf; ++a) {
      std::vector<Field> g(nc, zero);
      g[k] = f[a];
      P.col(k * nf + a) = bc.restrict(W.interpolate(g));
    }
  return P;
}

}  // namespace cdyn::testing
