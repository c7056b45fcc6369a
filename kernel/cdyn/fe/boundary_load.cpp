// fe/boundary_load.cpp — the Neumann term of the load, L_i = ∫_{Γ_N} g · φ_i ds (seed
// eq. 3), facet by facet (declared in fe/assembly.hpp).
//
// Each boundary facet is integrated as a facet of the cell that owns it, with the
// cell's basis, so every element is handled alike (bubbles vanish there, P2 edge
// functions do not): a point of the facet is mapped to the cell's reference
// coordinates by the same affine combination of the facet's vertices as in space.
//   1D: the facet is a point, ∫ g φ_i ds = g φ_i there;
//   2D: an edge [a, b], ds = |b − a| ds_ref, Gauss–Legendre in s ∈ [0, 1];
//   3D: a triangle (a, b, c), dS = |(b − a) × (c − a)| dS_ref on the reference
//       triangle (area ½), with its collapsed rule (fe/quadrature.hpp).
// The rules are exact for g φ_i with g of the degree of W^h plus 2 (as assemble_load).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/quadrature.hpp"

namespace cdyn {

namespace {

// The cell owning a boundary facet, and the local indices in it of the facet's
// vertices, in the facet's order: facet vertex m is the cell's local vertex k[m].
struct FacetInCell {
  int cell = -1;
  std::array<int, 3> k{-1, -1, -1};
};

// A facet's key: its d vertices sorted, the unused entries last (kUnused).
constexpr int kUnused = std::numeric_limits<int>::max();

std::vector<FacetInCell> locate_facets(const Mesh& mesh) {
  const int d = mesh.dim, nv = d + 1;
  // The facets of each cell (its vertices but one; in 1D a single vertex) by their
  // sorted vertices, with the local index of each of those sorted vertices.
  std::map<std::array<int, 3>, FacetInCell> owner;
  for (int c = 0; c < mesh.n_cells(); ++c)
    for (int skip = 0; skip < nv; ++skip) {
      std::array<std::pair<int, int>, 3> v;  // (vertex, local index)
      v.fill({kUnused, -1});
      for (int i = 0, m = 0; i < nv; ++i)
        if (i != skip) v[m++] = {mesh.cells[c][i], i};
      std::sort(v.begin(), v.end());
      FacetInCell f{c, {-1, -1, -1}};
      std::array<int, 3> key{kUnused, kUnused, kUnused};
      for (int m = 0; m < d; ++m) key[m] = v[m].first, f.k[m] = v[m].second;
      owner[key] = f;
    }
  std::vector<FacetInCell> out;
  for (const auto& facet : mesh.boundary) {
    std::array<int, 3> key{kUnused, kUnused, kUnused};
    std::copy(facet.vertices.begin(), facet.vertices.begin() + d, key.begin());
    std::sort(key.begin(), key.end());
    const auto it = owner.find(key);
    if (it == owner.end()) throw InputError("assemble_boundary_load: a boundary facet is not a facet of any cell");
    // put the local indices in the facet's own vertex order
    FacetInCell f{it->second.cell, {-1, -1, -1}};
    for (int m = 0; m < d; ++m)
      f.k[m] = it->second.k[std::find(key.begin(), key.begin() + d, facet.vertices[m]) - key.begin()];
    out.push_back(f);
  }
  return out;
}

// Reference coordinates of local vertex k of the reference interval / triangle /
// tetrahedron.
RefPoint reference_vertex(int dim, int k) {
  if (dim == 1) return {static_cast<double>(k), 0.0, 0.0};
  return {k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0, k == 3 ? 1.0 : 0.0};
}

}  // namespace

Eigen::VectorXd assemble_boundary_load(const FESpace& W, const std::vector<int>& parts, const std::vector<Field>& g,
                                       double t) {
  if (static_cast<int>(g.size()) != W.components())
    throw InputError("assemble_boundary_load: one field per component expected");
  const Mesh& mesh = W.mesh();
  const std::vector<FacetInCell> where = locate_facets(mesh);
  // A point facet (1D) is "integrated" by one evaluation with weight 1.
  const QuadratureRule rule = mesh.dim == 1   ? QuadratureRule{{{0.0, 0.0, 0.0}}, {1.0}}
                              : mesh.dim == 2 ? gauss_legendre(W.degree() + 2)
                                              : cell_quadrature(2, 2 * W.degree() + 2);
  Eigen::VectorXd L = Eigen::VectorXd::Zero(W.n_dofs());
  std::vector<double> phi(W.local_dofs());
  // a component uniform in space (Field::depends_on_space) is evaluated once
  std::vector<double> uniform_value(g.size(), 0.0);
  for (std::size_t c = 0; c < g.size(); ++c)
    if (!g[c].depends_on_space()) uniform_value[c] = g[c](Point{}, t);
  for (std::size_t f = 0; f < mesh.boundary.size(); ++f) {
    if (std::find(parts.begin(), parts.end(), mesh.boundary[f].part) == parts.end()) continue;
    const FacetInCell& k = where[f];
    const auto d = W.cell_dofs(k.cell);
    // ∫ over the facet = Σ_p w_p |J_facet| g(x_p) φ_i(ξ_p), with x_p and ξ_p the same
    // combination of the facet's vertices in space and in the cell's reference.
    auto add = [&](const RefPoint& xi, const Point& x, double weight, double jacobian) {
      shape_values(W.element(), W.dim(), xi, phi.data());
      for (int c = 0; c < W.components(); ++c) {
        const double gw = (g[c].depends_on_space() ? g[c](x, t) : uniform_value[c]) * weight * jacobian;
        for (int i = 0; i < W.local_dofs(); ++i) L[W.dof(d[i], c)] += gw * phi[i];
      }
    };
    const Point& a = mesh.vertices[mesh.cells[k.cell][k.k[0]]];
    const RefPoint xa = reference_vertex(mesh.dim, k.k[0]);
    if (mesh.dim <= 2) {
      const Point& b = mesh.dim == 1 ? a : mesh.vertices[mesh.cells[k.cell][k.k[1]]];
      const RefPoint xb = mesh.dim == 1 ? xa : reference_vertex(mesh.dim, k.k[1]);
      const double length = mesh.dim == 1 ? 1.0 : std::hypot(b.x - a.x, b.y - a.y);  // ds = |b − a| ds_ref
      for (int p = 0; p < rule.size(); ++p) {
        const double s = rule.points[p][0];  // position along the edge, a at s = 0
        add({(1 - s) * xa[0] + s * xb[0], (1 - s) * xa[1] + s * xb[1], 0.0},
            {(1 - s) * a.x + s * b.x, (1 - s) * a.y + s * b.y, (1 - s) * a.z + s * b.z}, rule.weights[p], length);
      }
      continue;
    }
    const Point& b = mesh.vertices[mesh.cells[k.cell][k.k[1]]];
    const Point& c = mesh.vertices[mesh.cells[k.cell][k.k[2]]];
    const RefPoint xb = reference_vertex(3, k.k[1]), xc = reference_vertex(3, k.k[2]);
    const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, w[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
    const double jacobian =  // |(b − a) × (c − a)| = twice the area
        std::hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]);
    for (int p = 0; p < rule.size(); ++p) {
      const double s = rule.points[p][0], r = rule.points[p][1], o = 1.0 - s - r;  // weights of b, c, a
      RefPoint xi;
      for (int e = 0; e < 3; ++e) xi[e] = o * xa[e] + s * xb[e] + r * xc[e];
      add(xi, {o * a.x + s * b.x + r * c.x, o * a.y + s * b.y + r * c.y, o * a.z + s * b.z + r * c.z},
          rule.weights[p], jacobian);
    }
  }
  return L;
}

}  // namespace cdyn
