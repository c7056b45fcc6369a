// contact_pressure.cpp — F_N, p and the gap at the vertices of Γ_C.
#include "cdyn/post/contact_pressure.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "cdyn/post/contact_force.hpp"

namespace cdyn {

ContactPressure::ContactPressure(const ConstrainedProblem& p, const std::vector<int>& contact_parts, Point plane_point,
                                 Point plane_normal)
    : p_(p), point_(plane_point) {
  // (the two-argument hypot in the plane, as the problem's builder normalizes n)
  const double norm = plane_normal.z == 0.0 ? std::hypot(plane_normal.x, plane_normal.y)
                                            : std::hypot(plane_normal.x, plane_normal.y, plane_normal.z);
  n_ = {plane_normal.x / norm, plane_normal.y / norm, plane_normal.z / norm};
  // w(a): half of each Γ_C edge to each of its two vertices.
  const Mesh& mesh = p.W->mesh();
  std::map<int, double> weight;
  for (const BoundaryFacet& f : mesh.boundary) {
    if (std::find(contact_parts.begin(), contact_parts.end(), f.part) == contact_parts.end()) continue;
    const Point &a = mesh.vertices[f.vertices[0]], &b = mesh.vertices[f.vertices[1]];
    const double half = 0.5 * std::hypot(b.x - a.x, b.y - a.y);
    weight[f.vertices[0]] += half;
    weight[f.vertices[1]] += half;
  }
  for (const auto& [v, w] : weight) {
    if (!is_constrained_vertex(p, v)) continue;
    const Point& a = mesh.vertices[v];
    vertices_.push_back({v, -(a.x - point_.x) * n_.y + (a.y - point_.y) * n_.x, w});
  }
  std::sort(vertices_.begin(), vertices_.end(), [](const Vertex& a, const Vertex& b) { return a.s < b.s; });
}

double ContactPressure::normal_force(const Eigen::VectorXd& reaction_xy, const Vertex& a) const {
  const Point F = vertex_force(p_, reaction_xy, a.vertex);
  return F.x * n_.x + F.y * n_.y + F.z * n_.z;
}

double ContactPressure::pressure(const Eigen::VectorXd& reaction_xy, const Vertex& a) const {
  return a.weight > 0.0 ? normal_force(reaction_xy, a) / a.weight : 0.0;
}

double ContactPressure::gap(const Eigen::VectorXd& U_full, const Vertex& a) const {
  const Point& x = p_.W->mesh().vertices[a.vertex];
  const FESpace& W = *p_.W;
  const double xa[3] = {x.x, x.y, x.z}, pa[3] = {point_.x, point_.y, point_.z}, n[3] = {n_.x, n_.y, n_.z};
  double g = 0.0;
  for (int k = 0; k < W.components(); ++k) g += (xa[k] + U_full[W.vertex_dof(a.vertex, k)] - pa[k]) * n[k];
  return g;
}

double ContactPressure::total_force(const Eigen::VectorXd& reaction_xy) const {
  double total = 0.0;
  for (const Vertex& a : vertices_) total += normal_force(reaction_xy, a);
  return total;
}

}  // namespace cdyn
