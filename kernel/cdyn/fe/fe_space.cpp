// fe/fe_space.cpp — dof maps, nodal interpolation and point evaluation.
#include "cdyn/fe/fe_space.hpp"

#include <algorithm>
#include <map>

#include "cdyn/mesh/cell_geometry.hpp"
#include "cdyn/base/error.hpp"

namespace cdyn {

FESpace::FESpace(const Mesh& mesh, Element element, int components)
    : mesh_(&mesh), element_(element), components_(components), local_dofs_(cdyn::local_dofs(element, mesh.dim)) {
  if (components != 1 && components != mesh.dim)
    throw InputError("a space has 1 component or one per coordinate (" + std::to_string(mesh.dim) + " components on this mesh)");
  const int nv = mesh.n_vertices(), nc = mesh.n_cells(), d = mesh.dim;
  cell_dofs_.resize(static_cast<std::size_t>(nc) * local_dofs_);
  auto centroid = [&](int c) { return CellGeometry(mesh, c).map(local_node(Element::P0, d, 0)); };

  if (element == Element::P0) {
    n_scalar_dofs_ = nc;
    for (int c = 0; c < nc; ++c) {
      cell_dofs_[c] = c;
      dof_points_.push_back(centroid(c));
    }
    return;
  }

  dof_points_ = mesh.vertices;
  for (int c = 0; c < nc; ++c)
    for (int k = 0; k <= d; ++k) cell_dofs_[static_cast<std::size_t>(c) * local_dofs_ + k] = mesh.cells[c][k];
  n_scalar_dofs_ = nv;

  const bool one_per_cell = element == Element::P1Bubble || (element == Element::P2 && d == 1);
  if (one_per_cell) {  // bubble, or the midpoint of a 1D P2 cell
    for (int c = 0; c < nc; ++c) {
      cell_dofs_[static_cast<std::size_t>(c) * local_dofs_ + d + 1] = nv + c;
      dof_points_.push_back(centroid(c));
    }
    n_scalar_dofs_ = nv + nc;
  } else if (element == Element::P2) {  // one dof per edge, numbered by first appearance
    std::map<std::pair<int, int>, int> index;
    for (int c = 0; c < nc; ++c)
      for (int e = 0; e < n_local_edges(d); ++e) {
        const auto [ka, kb] = local_edge(e);
        const int a = mesh.cells[c][ka], b = mesh.cells[c][kb];
        const auto key = std::minmax(a, b);
        auto [it, inserted] = index.try_emplace({key.first, key.second}, static_cast<int>(edges_.size()));
        if (inserted) {
          edges_.push_back({key.first, key.second});
          const Point& pa = mesh.vertices[a];
          const Point& pb = mesh.vertices[b];
          dof_points_.push_back({0.5 * (pa.x + pb.x), 0.5 * (pa.y + pb.y), 0.5 * (pa.z + pb.z)});
        }
        cell_dofs_[static_cast<std::size_t>(c) * local_dofs_ + d + 1 + e] = nv + it->second;
      }
    n_scalar_dofs_ = nv + static_cast<int>(edges_.size());
  }
}

std::vector<int> FESpace::boundary_scalar_dofs(const std::vector<int>& parts) const {
  if (element_ == Element::P0) return {};
  std::vector<int> s = mesh_->part_vertices(parts);
  if (element_ == Element::P2 && dim() >= 2) {
    // the edges of each facet: the facet itself in 2D, its three sides in 3D
    std::map<std::pair<int, int>, int> index;
    for (std::size_t e = 0; e < edges_.size(); ++e) index[{edges_[e][0], edges_[e][1]}] = static_cast<int>(e);
    for (const auto& f : mesh_->boundary) {
      if (std::find(parts.begin(), parts.end(), f.part) == parts.end()) continue;
      for (int i = 0; i < dim(); ++i)
        for (int j = i + 1; j < dim(); ++j) {
          const auto key = std::minmax(f.vertices[i], f.vertices[j]);
          s.push_back(mesh_->n_vertices() + index.at({key.first, key.second}));
        }
    }
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
  }
  return s;
}

Eigen::VectorXd FESpace::interpolate(const Field& f, double t) const {
  if (components_ != 1) throw InputError("interpolate: a vector space needs one field per component");
  return interpolate(std::vector<Field>{f}, t);
}

Eigen::VectorXd FESpace::interpolate(const std::vector<Field>& f, double t) const {
  if (static_cast<int>(f.size()) != components_) throw InputError("interpolate: one field per component expected");
  Eigen::VectorXd U(n_dofs());
  for (int s = 0; s < n_scalar_dofs_; ++s)
    for (int k = 0; k < components_; ++k) U[dof(s, k)] = f[k](dof_points_[s], t);
  if (element_ == Element::P1Bubble) {
    // Hierarchical bubble: its coefficient is f(centroid) minus the P1 part there
    // (every hat function equals 1/(dim+1) at the centroid).
    const int nv = dim() + 1;
    for (int c = 0; c < mesh_->n_cells(); ++c) {
      const auto dofs = cell_dofs(c);
      for (int k = 0; k < components_; ++k) {
        double p1 = 0.0;
        for (int i = 0; i < nv; ++i) p1 += U[dof(dofs[i], k)];
        U[dof(dofs[nv], k)] -= p1 / nv;
      }
    }
  }
  return U;
}

double FESpace::value_in_cell(const Eigen::VectorXd& U, int c, const RefPoint& xi, int k) const {
  double phi[kMaxLocalDofs];
  shape_values(element_, dim(), xi, phi);
  const auto dofs = cell_dofs(c);
  double u = 0.0;
  for (int i = 0; i < local_dofs_; ++i) u += U[dof(dofs[i], k)] * phi[i];
  return u;
}

}  // namespace cdyn
