// mesh/sub_mesh.cpp — the sub-mesh of some cells (mesh/sub_mesh.hpp).
#include "cdyn/mesh/sub_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "cdyn/base/error.hpp"

namespace cdyn {

SubMesh sub_mesh(const Mesh& mesh, const std::vector<int>& cells) {
  const int d = mesh.dim;
  SubMesh sub;
  sub.cell = cells;
  std::vector<char> taken(mesh.n_cells(), 0), held(mesh.n_vertices(), 0);
  for (int c : cells) {
    if (c < 0 || c >= mesh.n_cells()) throw InputError("sub_mesh: cell " + std::to_string(c) + " does not exist");
    if (taken[c]) throw InputError("sub_mesh: cell " + std::to_string(c) + " is listed twice");
    taken[c] = 1;
    for (int k = 0; k <= d; ++k) held[mesh.cells[c][k]] = 1;
  }
  // the vertices in the mesh's order, so that P_r keeps the order of the unknowns
  std::vector<int> local(mesh.n_vertices(), -1);
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (held[v]) {
      local[v] = static_cast<int>(sub.vertex.size());
      sub.vertex.push_back(v);
    }

  Mesh& m = sub.mesh;
  m.dim = d;
  m.part_names = mesh.part_names;
  m.region_names = mesh.region_names;
  for (int v : sub.vertex) m.vertices.push_back(mesh.vertices[v]);
  std::set<FacetKey> own_facets;  // the facets of the sub-mesh's cells, in the mesh's vertices
  for (int c : cells) {
    Cell cell{-1, -1, -1, -1};
    for (int k = 0; k <= d; ++k) cell[k] = local[mesh.cells[c][k]];
    m.cells.push_back(cell);
    if (!mesh.cell_region.empty()) m.cell_region.push_back(mesh.cell_region[c]);
    for (int skip = 0; skip <= d; ++skip) own_facets.insert(cell_facet(mesh.cells[c], d, skip));
  }

  // A boundary facet lies in exactly one cell: it is this sub-mesh's when its cell is.
  // The others' vertices held here are on their part all the same.
  for (const BoundaryFacet& f : mesh.boundary) {
    if (own_facets.count(facet_key(f.vertices, d))) {
      BoundaryFacet g = f;
      for (int k = 0; k < d; ++k) g.vertices[k] = local[f.vertices[k]];
      m.boundary.push_back(g);
    } else if (f.part >= 0) {
      for (int k = 0; k < d; ++k)
        if (local[f.vertices[k]] >= 0) m.parts_elsewhere.push_back({f.part, local[f.vertices[k]]});
    }
  }
  for (const auto& [part, v] : mesh.parts_elsewhere)
    if (local[v] >= 0) m.parts_elsewhere.push_back({part, local[v]});
  std::sort(m.parts_elsewhere.begin(), m.parts_elsewhere.end());
  m.parts_elsewhere.erase(std::unique(m.parts_elsewhere.begin(), m.parts_elsewhere.end()), m.parts_elsewhere.end());
  return sub;
}

std::vector<int> slab_cells(const Mesh& mesh, int part, int parts) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Point& v : mesh.vertices) lo = std::min(lo, v.x), hi = std::max(hi, v.x);
  std::vector<int> cells;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    double x = 0;
    for (int k = 0; k <= mesh.dim; ++k) x += mesh.vertices[mesh.cells[c][k]].x / (mesh.dim + 1);
    const int slab = hi > lo ? static_cast<int>((x - lo) / (hi - lo) * parts) : 0;
    if (std::min(slab, parts - 1) == part) cells.push_back(c);
  }
  return cells;
}

CellGraph cell_graph(const Mesh& mesh) {
  const int d = mesh.dim;
  // each facet with the cells that have it: sorted by facet, a shared facet's two
  // cells come together
  std::vector<std::pair<FacetKey, int>> facets;
  facets.reserve(static_cast<std::size_t>(mesh.n_cells()) * (d + 1));
  for (int c = 0; c < mesh.n_cells(); ++c)
    for (int k = 0; k <= d; ++k) facets.emplace_back(cell_facet(mesh.cells[c], d, k), c);
  std::sort(facets.begin(), facets.end());
  std::vector<std::vector<int>> neighbours(mesh.n_cells());
  for (std::size_t i = 0; i + 1 < facets.size(); ++i)
    if (facets[i].first == facets[i + 1].first) {
      neighbours[facets[i].second].push_back(facets[i + 1].second);
      neighbours[facets[i + 1].second].push_back(facets[i].second);
    }
  CellGraph g;
  g.offset.push_back(0);
  for (std::vector<int>& n : neighbours) {
    std::sort(n.begin(), n.end());
    g.neighbour.insert(g.neighbour.end(), n.begin(), n.end());
    g.offset.push_back(static_cast<int>(g.neighbour.size()));
  }
  return g;
}

}  // namespace cdyn
