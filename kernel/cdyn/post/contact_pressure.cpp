// contact_pressure.cpp — F_N, p and the gap at the contact vertices; the penetration of
// the whole boundary.
#include "cdyn/post/contact_pressure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "cdyn/base/error.hpp"
#include "cdyn/post/contact_force.hpp"

namespace cdyn {

namespace {

// φ(a + u(a), t)/scale: the distance of the displaced vertex to the obstacle.
double distance(const ConstrainedProblem& p, const RigidObstacle& o, int vertex, double scale,
                const Eigen::VectorXd& U_full, double t) {
  const Point& a = p.W->mesh().vertices[vertex];
  const FESpace& W = *p.W;
  double x[3] = {a.x, a.y, a.z};
  for (int k = 0; k < W.components(); ++k) x[k] += U_full[W.vertex_dof(vertex, k)];
  return o.gap(Point{x[0], x[1], x[2]}, t) / scale;
}

}  // namespace

ContactPressure::ContactPressure(const ConstrainedProblem& p) : p_(p) {
  const Mesh& mesh = p.W->mesh();
  std::map<int, int> node_of;
  for (int k = 0; k < static_cast<int>(p.contact_nodes.size()); ++k) node_of[p.contact_nodes[k].vertex] = k;
  // w(a): the share ∫_F φ_a = |F|/d of each Γ_C facet F (an edge, d = 2, or a triangle,
  // d = 3) to each of its vertices (the facets of the parts of the vertex's obstacle).
  const int d = mesh.dim;
  std::map<int, double> weight;
  for (const BoundaryFacet& f : mesh.boundary) {
    bool all = true;
    for (int k = 0; k < d; ++k) all = all && node_of.count(f.vertices[k]) > 0;
    if (!all) continue;
    const std::vector<int>& parts = p.obstacles[p.contact_nodes[node_of.at(f.vertices[0])].obstacle].contact_parts;
    if (std::find(parts.begin(), parts.end(), f.part) == parts.end()) continue;
    const Point &pa = mesh.vertices[f.vertices[0]], &pb = mesh.vertices[f.vertices[1]];
    double share = 0.0;
    if (d == 2) {
      share = 0.5 * std::hypot(pb.x - pa.x, pb.y - pa.y);
    } else {
      const Point& pc = mesh.vertices[f.vertices[2]];
      const double u[3] = {pb.x - pa.x, pb.y - pa.y, pb.z - pa.z}, w[3] = {pc.x - pa.x, pc.y - pa.y, pc.z - pa.z};
      const double area = 0.5 * std::hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]);
      share = area / 3.0;
    }
    for (int k = 0; k < d; ++k) weight[f.vertices[k]] += share;
  }
  for (const auto& [v, w] : weight) {
    if (!is_constrained_vertex(p, v)) continue;
    const ConstrainedProblem::ContactNode& c = p.contact_nodes[node_of.at(v)];
    const Point& a = mesh.vertices[v];
    const Point& o = p.obstacles[c.obstacle].origin;
    const Point& n = c.normal;
    double s = -(a.x - o.x) * n.y + (a.y - o.y) * n.x;
    if (d == 3) {  // the distance from the origin along the obstacle: |(a − o) − ((a − o)·n) n|
      const double r[3] = {a.x - o.x, a.y - o.y, a.z - o.z};
      const double rn = r[0] * n.x + r[1] * n.y + r[2] * n.z;
      s = std::hypot(r[0] - rn * n.x, r[1] - rn * n.y, r[2] - rn * n.z);
    }
    vertices_.push_back({v, s, w, node_of.at(v)});
  }
  std::sort(vertices_.begin(), vertices_.end(), [this](const Vertex& a, const Vertex& b) {
    const int oa = p_.contact_nodes[a.node].obstacle, ob = p_.contact_nodes[b.node].obstacle;
    return oa != ob ? oa < ob : a.s != b.s ? a.s < b.s : a.vertex < b.vertex;
  });
}

double ContactPressure::normal_force(const Eigen::VectorXd& reaction_xy, const Vertex& a) const {
  const Point F = vertex_force(p_, reaction_xy, a.vertex);
  const Point& n = node(a).normal;
  return F.x * n.x + F.y * n.y + F.z * n.z;
}

double ContactPressure::pressure(const Eigen::VectorXd& reaction_xy, const Vertex& a) const {
  return a.weight > 0.0 ? normal_force(reaction_xy, a) / a.weight : 0.0;
}

double ContactPressure::gap(const Eigen::VectorXd& U_full, const Vertex& a, double t) const {
  const ConstrainedProblem::ContactNode& c = node(a);
  return distance(p_, p_.obstacles[c.obstacle], a.vertex, c.scale, U_full, t);
}

double ContactPressure::total_force(const Eigen::VectorXd& reaction_xy) const {
  double total = 0.0;
  for (const Vertex& a : vertices_) total += normal_force(reaction_xy, a);
  return total;
}

BoundaryPenetration::BoundaryPenetration(const ConstrainedProblem& p) : p_(p) {
  const Mesh& mesh = p.W->mesh();
  std::vector<int> all_parts{-1};
  for (int k = 0; k < static_cast<int>(mesh.part_names.size()); ++k) all_parts.push_back(k);
  vertices_ = mesh.part_vertices(all_parts);
  const double h = 1e-6 * mesh.h_max();
  for (const RigidObstacle& o : p.obstacles) {
    std::vector<double> s;
    for (int v : vertices_) {
      double scale = 1.0;  // (where φ has no gradient, e.g. a cylinder's axis, φ itself)
      try {
        scale = obstacle_normal(o, mesh.vertices[v], h, mesh.dim).scale;
      } catch (const InputError&) {
      }
      s.push_back(scale);
    }
    scale_.push_back(std::move(s));
  }
}

double BoundaryPenetration::operator()(const Eigen::VectorXd& U_full, double t) const {
  double worst = 0.0;
  for (std::size_t k = 0; k < p_.obstacles.size(); ++k)
    for (std::size_t j = 0; j < vertices_.size(); ++j)
      worst = std::max(worst, -distance(p_, p_.obstacles[k], vertices_[j], scale_[k][j], U_full, t));
  return worst;
}

}  // namespace cdyn
