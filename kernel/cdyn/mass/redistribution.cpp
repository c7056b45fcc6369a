// redistribution.cpp — the affine-extrapolation operator T (see the header).
#include "cdyn/mass/redistribution.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

constexpr int kMaxRings = 6;  // donors further than this many cells away: give up

// Vertex neighbours through the cells (each vertex's list sorted, unique).
std::vector<std::vector<int>> vertex_adjacency(const Mesh& mesh) {
  std::vector<std::vector<int>> adj(mesh.n_vertices());
  const int nv = mesh.vertices_per_cell();
  for (const auto& cell : mesh.cells)
    for (int a = 0; a < nv; ++a)
      for (int b = 0; b < nv; ++b)
        if (a != b) adj[cell[a]].push_back(cell[b]);
  for (auto& l : adj) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  return adj;
}

}  // namespace

SparseMatrix redistribution_operator(const FESpace& W, const DirichletLift& bc,
                                     const std::vector<int>& contact_free_dofs) {
  const Mesh& mesh = W.mesh();
  const int n = bc.n_free(), nc = W.components(), dim = mesh.dim;
  if (!W.has_vertex_dofs()) throw InputError("mass redistributed: the displacement space must be continuous");
  std::vector<char> contact(n, 0);
  for (int i : contact_free_dofs) {
    if (i < 0 || i >= n)
      throw InputError("mass redistributed: contact dof " + std::to_string(i) + " is not a free dof (0.." +
                       std::to_string(n - 1) + ")");
    if (bc.free_dofs()[i] / nc >= mesh.n_vertices())
      throw InputError("mass redistributed: contact dof " + std::to_string(i) +
                       " is not a vertex dof (constraints act on vertex values only)");
    contact[i] = 1;
  }
  const auto adj = vertex_adjacency(mesh);

  std::vector<Eigen::Triplet<double>> t;
  t.reserve(n + 16 * contact_free_dofs.size());
  std::vector<int> seen_at(mesh.n_vertices(), -1);  // BFS marks, stamped with the contact dof
  for (int i = 0; i < n; ++i) {
    if (!contact[i]) {
      t.emplace_back(i, i, 1.0);
      continue;
    }
    const int g = bc.free_dofs()[i], s = g / nc, k = g % nc;
    const Point& ac = mesh.vertices[s];
    // Ring-by-ring walk; donors are free, non-contact dofs of component k.
    std::vector<int> donors;  // free indices
    std::vector<Point> where;
    std::vector<int> ring{s};
    seen_at[s] = i;
    bool found = false;
    for (int level = 1; level <= kMaxRings && !found && !ring.empty(); ++level) {
      std::vector<int> next;
      for (int v : ring)
        for (int u : adj[v])
          if (seen_at[u] != i) {
            seen_at[u] = i;
            next.push_back(u);
            const int f = bc.free_index(W.vertex_dof(u, k));
            if (f >= 0 && !contact[f]) {
              donors.push_back(f);
              where.push_back(mesh.vertices[u]);
            }
          }
      ring = std::move(next);
      if (static_cast<int>(donors.size()) < dim + 1) continue;
      // Moment equations Pᵀ w = p(a_c) in coordinates centred at a_c and scaled by the
      // donors' distance, so that the rank test and the weights are scale-free.
      double h = 0.0;
      for (const Point& p : where)
        h = std::max(h, dim == 3 ? std::hypot(p.x - ac.x, p.y - ac.y, p.z - ac.z) : std::hypot(p.x - ac.x, p.y - ac.y));
      Eigen::MatrixXd Pt(dim + 1, donors.size());
      for (std::size_t j = 0; j < donors.size(); ++j) {
        Pt(0, j) = 1.0;
        Pt(1, j) = (where[j].x - ac.x) / h;
        if (dim >= 2) Pt(2, j) = (where[j].y - ac.y) / h;
        if (dim == 3) Pt(3, j) = (where[j].z - ac.z) / h;
      }
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(Pt);
      // affinely dependent donors (all on one line, or in 3D on one plane): keep walking
      cod.setThreshold(1e-8);
      if (cod.rank() < dim + 1) continue;
      Eigen::VectorXd e0 = Eigen::VectorXd::Zero(dim + 1);
      e0[0] = 1.0;  // (1, 0, ...): the value at a_c of 1, x − x_c, y − y_c, z − z_c
      const Eigen::VectorXd w = cod.solve(e0);  // minimum-norm solution
      for (std::size_t j = 0; j < donors.size(); ++j) t.emplace_back(i, donors[j], w[j]);
      found = true;
    }
    if (!found)
      throw InputError("mass redistributed: contact vertex " + std::to_string(s) +
                       (donors.empty() ? std::string(" has no non-contact free vertices near it to carry its mass "
                                                     "(every free vertex in contact? redistribution is for a contact "
                                                     "boundary; use a pair such as P1+/P0 for a volume obstacle)")
                                       : std::string(" has no affinely independent donors near it (the non-contact free "
                                                     "vertices all lie on one line or plane, e.g. a body one cell thick; use a "
                                                     "pair such as P1+/P0)")));
  }
  SparseMatrix T(n, n);
  T.setFromTriplets(t.begin(), t.end());
  T.makeCompressed();
  return T;
}

}  // namespace cdyn
