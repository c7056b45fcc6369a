// fe/element.cpp — basis functions of P0, P1, P1+, P2 in barycentric coordinates.
#include "cdyn/fe/element.hpp"

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

using Vec3 = std::array<double, 3>;  // a reference point or gradient (ξ, η, ζ)

// Barycentric coordinates of the reference cell and their (constant) gradients (the
// entries beyond dim + 1 are 0).
struct Barycentric {
  double l[4] = {0.0, 0.0, 0.0, 0.0};
  Vec3 dl[4] = {};
  Barycentric(int dim, const Vec3& xi) {
    if (dim == 1) {
      l[0] = 1.0 - xi[0], l[1] = xi[0];
      dl[0] = {-1.0, 0.0, 0.0}, dl[1] = {1.0, 0.0, 0.0};
    } else if (dim == 2) {
      l[0] = 1.0 - xi[0] - xi[1], l[1] = xi[0], l[2] = xi[1];
      dl[0] = {-1.0, -1.0, 0.0}, dl[1] = {1.0, 0.0, 0.0}, dl[2] = {0.0, 1.0, 0.0};
    } else {
      l[0] = 1.0 - xi[0] - xi[1] - xi[2], l[1] = xi[0], l[2] = xi[1], l[3] = xi[2];
      dl[0] = {-1.0, -1.0, -1.0}, dl[1] = {1.0, 0.0, 0.0}, dl[2] = {0.0, 1.0, 0.0}, dl[3] = {0.0, 0.0, 1.0};
    }
  }
};

// Local edges of the tetrahedron, in the order of the P2 edge dofs; the first three
// are the triangle's.
constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

Vec3 scale(double a, const Vec3& x) { return {a * x[0], a * x[1], a * x[2]}; }

Vec3 axpy(double a, const Vec3& x, double b, const Vec3& y) {
  return {a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2]};
}

}  // namespace

std::string to_string(Element e) {
  switch (e) {
    case Element::P0: return "P0";
    case Element::P1: return "P1";
    case Element::P1Bubble: return "P1+";
    case Element::P2: return "P2";
  }
  return "?";
}

Element element_from_string(const std::string& name) {
  if (name == "P0") return Element::P0;
  if (name == "P1") return Element::P1;
  if (name == "P1+" || name == "P1b") return Element::P1Bubble;
  if (name == "P2") return Element::P2;
  throw InputError("unknown finite element '" + name + "' (expected P0, P1, P1+ or P2)");
}

int local_dofs(Element e, int dim) {
  switch (e) {
    case Element::P0: return 1;
    case Element::P1: return dim + 1;
    case Element::P1Bubble: return dim + 2;
    case Element::P2: return (dim + 1) * (dim + 2) / 2;  // 3, 6, 10
  }
  return 0;
}

int polynomial_degree(Element e, int dim) {
  switch (e) {
    case Element::P0: return 0;
    case Element::P1: return 1;
    case Element::P1Bubble: return dim + 1;
    case Element::P2: return 2;
  }
  return 0;
}

void shape_values(Element e, int dim, const RefPoint& xi, double* v) {
  const Barycentric b(dim, xi);
  const int nv = dim + 1;
  switch (e) {
    case Element::P0:
      v[0] = 1.0;
      return;
    case Element::P1:
      for (int k = 0; k < nv; ++k) v[k] = b.l[k];
      return;
    case Element::P1Bubble:
      for (int k = 0; k < nv; ++k) v[k] = b.l[k];
      v[nv] = dim == 1   ? 4.0 * b.l[0] * b.l[1]
              : dim == 2 ? 27.0 * b.l[0] * b.l[1] * b.l[2]
                         : 256.0 * b.l[0] * b.l[1] * b.l[2] * b.l[3];
      return;
    case Element::P2:
      for (int k = 0; k < nv; ++k) v[k] = b.l[k] * (2.0 * b.l[k] - 1.0);
      if (dim == 1) {
        v[2] = 4.0 * b.l[0] * b.l[1];
      } else {
        for (int k = 0; k < n_local_edges(dim); ++k) v[nv + k] = 4.0 * b.l[kEdge[k][0]] * b.l[kEdge[k][1]];
      }
      return;
  }
}

void shape_gradients(Element e, int dim, const RefPoint& xi, Vec3* g) {
  const Barycentric b(dim, xi);
  const int nv = dim + 1;
  switch (e) {
    case Element::P0:
      g[0] = {0.0, 0.0, 0.0};
      return;
    case Element::P1:
      for (int k = 0; k < nv; ++k) g[k] = b.dl[k];
      return;
    case Element::P1Bubble:
      for (int k = 0; k < nv; ++k) g[k] = b.dl[k];
      if (dim == 1) {
        g[nv] = axpy(4.0 * b.l[1], b.dl[0], 4.0 * b.l[0], b.dl[1]);
      } else if (dim == 2) {
        // ∇(27 λ0λ1λ2) = 27 (λ1λ2 ∇λ0 + λ0λ2 ∇λ1 + λ0λ1 ∇λ2)
        const Vec3 g01 = axpy(b.l[1] * b.l[2], b.dl[0], b.l[0] * b.l[2], b.dl[1]);
        g[nv] = axpy(27.0, g01, 27.0 * b.l[0] * b.l[1], b.dl[2]);
      } else {
        // ∇(256 λ0λ1λ2λ3) = 256 Σ_k (Π_{j≠k} λj) ∇λk
        const double l0 = b.l[0], l1 = b.l[1], l2 = b.l[2], l3 = b.l[3];
        const Vec3 g01 = axpy(l1 * l2 * l3, b.dl[0], l0 * l2 * l3, b.dl[1]);
        const Vec3 g23 = axpy(l0 * l1 * l3, b.dl[2], l0 * l1 * l2, b.dl[3]);
        g[nv] = axpy(256.0, g01, 256.0, g23);
      }
      return;
    case Element::P2:
      for (int k = 0; k < nv; ++k) g[k] = scale(4.0 * b.l[k] - 1.0, b.dl[k]);
      if (dim == 1) {
        g[2] = axpy(4.0 * b.l[1], b.dl[0], 4.0 * b.l[0], b.dl[1]);
      } else {
        for (int k = 0; k < n_local_edges(dim); ++k) {
          const int i = kEdge[k][0], j = kEdge[k][1];
          g[nv + k] = axpy(4.0 * b.l[j], b.dl[i], 4.0 * b.l[i], b.dl[j]);
        }
      }
      return;
  }
}

RefPoint local_node(Element e, int dim, int k) {
  const RefPoint vertex[4] = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  const RefPoint centroid = dim == 1   ? RefPoint{0.5, 0.0, 0.0}
                            : dim == 2 ? RefPoint{1.0 / 3.0, 1.0 / 3.0, 0.0}
                                       : RefPoint{0.25, 0.25, 0.25};
  const int nv = dim + 1;
  if (e == Element::P0) return centroid;
  if (k < nv) return vertex[k];
  if (e == Element::P1Bubble) return centroid;
  if (dim == 1) return {0.5, 0.0, 0.0};
  const RefPoint& a = vertex[kEdge[k - nv][0]];
  const RefPoint& b = vertex[kEdge[k - nv][1]];
  return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
}

int n_local_edges(int dim) { return dim == 3 ? 6 : dim == 2 ? 3 : 0; }

std::array<int, 2> local_edge(int k) { return {kEdge[k][0], kEdge[k][1]}; }

}  // namespace cdyn
