// contact_force.cpp — the constraint force per vertex, in (x, y).
#include "cdyn/post/contact_force.hpp"

#include <cmath>

namespace cdyn {

Eigen::VectorXd reaction_xy(const ConstrainedProblem& p, const Eigen::VectorXd& reaction) {
  if (reaction.size() == 0) return reaction;
  return p.global(reaction);
}

Point vertex_force(const ConstrainedProblem& p, const Eigen::VectorXd& reaction_xy, int vertex) {
  double F[3] = {0.0, 0.0, 0.0};
  if (reaction_xy.size() == 0) return {};
  for (int k = 0; k < p.W->components(); ++k) {
    const int i = p.bc->free_index(p.W->vertex_dof(vertex, k));
    if (i >= 0) F[k] = reaction_xy[i];
  }
  return {F[0], F[1], F[2]};
}

bool is_constrained_vertex(const ConstrainedProblem& p, int vertex) {
  for (int k = 0; k < p.W->components(); ++k) {
    const int i = p.bc->free_index(p.W->vertex_dof(vertex, k));
    if (i >= 0 && (std::isfinite(p.lower[i]) || std::isfinite(p.upper[i]))) return true;
  }
  return false;
}

Point vertex_multiplier(const ConstrainedProblem& p, const Eigen::VectorXd& reaction_xy, int vertex) {
  if (reaction_xy.size() == 0 || !is_constrained_vertex(p, vertex)) return {};
  const Point F = vertex_force(p, reaction_xy, vertex);
  return {0.0 - F.x, 0.0 - F.y, 0.0 - F.z};  // (0.0 − : no printed −0)
}

Eigen::VectorXd tangential_xy(const ConstrainedProblem& p, const Eigen::VectorXd& v) {
  if (v.size() == 0) return v;
  Eigen::VectorXd tangential = Eigen::VectorXd::Zero(v.size());
  for (const FrictionNode& node : p.friction)
    for (int t : node.tangential) tangential[t] = v[t];
  return p.global(tangential);
}

}  // namespace cdyn
