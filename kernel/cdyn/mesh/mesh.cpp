// mesh/mesh.cpp — simplicial meshes: measures, boundary bookkeeping, structured meshes.
#include "cdyn/mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <map>

#include "cdyn/base/error.hpp"

namespace cdyn {

int Mesh::part_index(const std::string& name) const {
  for (std::size_t p = 0; p < part_names.size(); ++p)
    if (part_names[p] == name) return static_cast<int>(p);
  std::string known;
  for (const auto& n : part_names) known += (known.empty() ? "" : ", ") + n;
  throw InputError("boundary part '" + name + "' does not exist (mesh has: " +
                   (known.empty() ? "none" : known) + ")");
}

std::vector<int> Mesh::part_vertices(const std::vector<int>& parts) const {
  std::vector<int> v;
  for (const auto& f : boundary) {
    if (std::find(parts.begin(), parts.end(), f.part) == parts.end()) continue;
    for (int k = 0; k < dim; ++k) v.push_back(f.vertices[k]);
  }
  for (const auto& [part, vertex] : parts_elsewhere)
    if (std::find(parts.begin(), parts.end(), part) != parts.end()) v.push_back(vertex);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

double Mesh::cell_measure(int c) const {
  const auto& t = cells[c];
  const Point& a = vertices[t[0]];
  const Point& b = vertices[t[1]];
  if (dim == 1) return b.x - a.x;
  const Point& p = vertices[t[2]];
  if (dim == 2) return 0.5 * ((b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y));
  // det[b − a, p − a, q − a] / 6
  const Point& q = vertices[t[3]];
  const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, v[3] = {p.x - a.x, p.y - a.y, p.z - a.z},
               w[3] = {q.x - a.x, q.y - a.y, q.z - a.z};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

double Mesh::measure() const {
  double s = 0.0;
  for (int c = 0; c < n_cells(); ++c) s += cell_measure(c);
  return s;
}

double Mesh::h_max() const {
  double h = 0.0;
  for (const auto& t : cells)
    for (int i = 0; i <= dim; ++i)
      for (int j = i + 1; j <= dim; ++j) {
        const Point& a = vertices[t[i]];
        const Point& b = vertices[t[j]];
        h = std::max(h, dim < 3 ? std::hypot(b.x - a.x, b.y - a.y) : std::hypot(b.x - a.x, b.y - a.y, b.z - a.z));
      }
  return h;
}

FacetKey facet_key(const std::array<int, 3>& vertices, int dim) {
  FacetKey k{-1, -1, -1};
  std::copy(vertices.begin(), vertices.begin() + dim, k.begin());
  // insertion sort of at most three entries (std::sort with a bound of dim trips GCC 12's
  // -Warray-bounds)
  for (int i = 1; i < dim; ++i)
    for (int j = i; j > 0 && k[j - 1] > k[j]; --j) std::swap(k[j - 1], k[j]);
  return k;
}

FacetKey cell_facet(const Cell& cell, int dim, int skip) {
  std::array<int, 3> f{-1, -1, -1};
  for (int k = 0; k < dim; ++k) f[k] = cell[(skip + 1 + k) % (dim + 1)];
  return facet_key(f, dim);
}

void Mesh::complete_boundary() {
  std::map<FacetKey, int> count;
  for (const auto& t : cells)
    for (int skip = 0; skip <= dim; ++skip) ++count[cell_facet(t, dim, skip)];
  std::map<FacetKey, bool> known;
  for (const auto& f : boundary) known[facet_key(f.vertices, dim)] = true;
  for (const auto& [k, n] : count)
    if (n == 1 && !known.count(k)) boundary.push_back({k, -1});
}

void Mesh::check(const std::string& source) const {
  if (dim < 1 || dim > 3) throw InputError(source + ": mesh dimension must be 1, 2 or 3");
  if (cells.empty()) throw InputError(source + ": the mesh has no cells");
  for (int c = 0; c < n_cells(); ++c) {
    for (int i = 0; i <= dim; ++i)
      if (cells[c][i] < 0 || cells[c][i] >= n_vertices())
        throw InputError(source + ": cell " + std::to_string(c) + " refers to a missing vertex");
    if (!(cell_measure(c) > 0.0))
      throw InputError(source + ": cell " + std::to_string(c) +
                       " is degenerate or inverted (measure " + std::to_string(cell_measure(c)) + ")");
  }
}

Mesh interval_mesh(int n, double length) {
  if (n < 1) throw InputError("n", "the interval needs at least one cell");
  // (isfinite: an infinite length would give the vertices inf·0 = NaN)
  if (!(length > 0.0) || !std::isfinite(length)) throw InputError("length", "must be positive and finite");
  // vertex indices are ints
  if (n >= std::numeric_limits<int>::max()) throw InputError("n", "too many cells (" + std::to_string(n) + ")");
  Mesh m;
  m.dim = 1;
  for (int i = 0; i <= n; ++i) m.vertices.push_back({length * i / n, 0.0});
  for (int i = 0; i < n; ++i) m.cells.push_back({i, i + 1, -1, -1});
  m.part_names = {"left", "right"};
  m.boundary = {{{0, -1, -1}, 0}, {{n, -1, -1}, 1}};
  return m;
}

Mesh unit_square_mesh(int n, double lx, double ly) {
  if (n < 1) throw InputError("n", "the square needs at least one cell per side");
  // (n + 1)² vertices and 2n² cells are indexed by int: refuse n where that overflows
  if (n > 46339) throw InputError("n", "too many cells per side (" + std::to_string(n) + "; at most 46339)");
  if (!(lx > 0.0 && ly > 0.0) || !std::isfinite(lx) || !std::isfinite(ly))
    throw InputError("unit_square_mesh: the side lengths must be positive and finite");
  Mesh m;
  m.dim = 2;
  auto v = [n](int i, int j) { return i + j * (n + 1); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back({lx * i / n, ly * j / n});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Split along the diagonal (i,j)-(i+1,j+1): lower-right then upper-left triangle.
      m.cells.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1), -1});
      m.cells.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1), -1});
    }
  m.part_names = {"bottom", "right", "top", "left"};
  for (int i = 0; i < n; ++i) {
    m.boundary.push_back({{v(i, 0), v(i + 1, 0), -1}, 0});
    m.boundary.push_back({{v(n, i), v(n, i + 1), -1}, 1});
    m.boundary.push_back({{v(i + 1, n), v(i, n), -1}, 2});
    m.boundary.push_back({{v(0, i + 1), v(0, i), -1}, 3});
  }
  return m;
}

Mesh unit_cube_mesh(int n) {
  if (n < 1) throw InputError("n", "the cube needs at least one cell per side");
  // 6n³ cells are indexed by int: refuse n where that overflows
  if (n > 710) throw InputError("n", "too many cells per side (" + std::to_string(n) + "; at most 710)");
  Mesh m;
  m.dim = 3;
  const int np = n + 1;
  auto v = [np](int i, int j, int k) { return i + np * (j + np * k); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.vertices.push_back({double(i) / n, double(j) / n, double(k) / n});

  // Kuhn's six tetrahedra: walk from the lowest corner to the highest one along the
  // axes a, b, c in turn.  The volume is det[e_a, e_a + e_b, e_a + e_b + e_c]/6 =
  // sign(a, b, c)/6, so the last two vertices are swapped for the odd orderings.
  constexpr int kOrder[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int p = 0; p < 6; ++p) {
          int at[3] = {i, j, k};
          Cell t{v(i, j, k), -1, -1, -1};
          for (int s = 0; s < 3; ++s) {
            ++at[kOrder[p][s]];
            t[s + 1] = v(at[0], at[1], at[2]);
          }
          if (p >= 3) std::swap(t[2], t[3]);
          m.cells.push_back(t);
        }

  // A square face with corners a, b, c, d counter-clockwise seen from outside and a, c
  // its lowest and highest corners: the triangles (a, b, c), (a, c, d) are the faces of
  // the tetrahedra that touch it.
  m.part_names = {"front", "right", "back", "left", "bottom", "top"};
  auto square = [&m](int a, int b, int c, int d, int part) {
    m.boundary.push_back({{a, b, c}, part});
    m.boundary.push_back({{a, c, d}, part});
  };
  for (int q = 0; q < n; ++q)
    for (int r = 0; r < n; ++r) {
      square(v(q, 0, r), v(q + 1, 0, r), v(q + 1, 0, r + 1), v(q, 0, r + 1), 0);  // y = 0, normal −e_y
      square(v(n, q, r), v(n, q + 1, r), v(n, q + 1, r + 1), v(n, q, r + 1), 1);  // x = 1, +e_x
      square(v(q, n, r), v(q, n, r + 1), v(q + 1, n, r + 1), v(q + 1, n, r), 2);  // y = 1, +e_y
      square(v(0, q, r), v(0, q, r + 1), v(0, q + 1, r + 1), v(0, q + 1, r), 3);  // x = 0, −e_x
      square(v(q, r, 0), v(q, r + 1, 0), v(q + 1, r + 1, 0), v(q + 1, r, 0), 4);  // z = 0, −e_z
      square(v(q, r, n), v(q + 1, r, n), v(q + 1, r + 1, n), v(q, r + 1, n), 5);  // z = 1, +e_z
    }
  return m;
}

}  // namespace cdyn
