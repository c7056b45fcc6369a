// contact_pressure.hpp — normal contact force, pressure and gap at the contact vertices of
// an elastic contact problem (problems/elastic_contact.hpp), each against the rigid
// obstacle that constrains it (problems/rigid_obstacle.hpp).
//
// The normal force on a constrained vertex a is F_N(a) = F(a)·n(a) = −λ_N(a) ≥ 0, F the
// step's reaction at a in (x, y) (post/contact_force.hpp) and n(a) the obstacle's unit
// outward normal there: a nodal force, the weak form's integral of the contact pressure
// against the vertex's hat function.  The pressure is p(a) = F_N(a) / w(a),
// w(a) = ∫_{Γ_C} φ_a ds the vertex's share of Γ_C (half the length of its contact edges,
// a third of the area of its contact triangles in space: the P1 hat function on the
// boundary, whatever W^h is, since the constraint is nodal at the vertices), so that Σ_a F_N(a) = Σ_a p(a) w(a) is the total contact force.  The gap
// is the distance φ(a + u(a), t)/|∇φ(a, 0)| to the obstacle, negative where the body
// penetrates it ((a + u(a) − p)·n for a plane).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "cdyn/problems/constrained_problem.hpp"

namespace cdyn {

class ContactPressure {
 public:
  struct Vertex {
    int vertex;
    double s;       // coordinate along the obstacle, (a − p)·t, t = (−n_y, n_x), p its origin;
                    // in space the distance |(a − p) − ((a − p)·n) n| from p along it
    double weight;  // w(a) = ∫_{Γ_C} φ_a ds
    int node;       // into ConstrainedProblem::contact_nodes
  };

  // The constrained contact vertices of p, sorted by obstacle, then by s, then by vertex.
  explicit ContactPressure(const ConstrainedProblem& p);

  const std::vector<Vertex>& vertices() const { return vertices_; }
  const ConstrainedProblem::ContactNode& node(const Vertex& a) const { return p_.contact_nodes[a.node]; }

  // F_N(a) of a step's Cartesian reaction (post/contact_force.hpp's reaction_xy).
  double normal_force(const Eigen::VectorXd& reaction_xy, const Vertex& a) const;
  // p(a) = F_N(a) / w(a) (0 where w = 0).
  double pressure(const Eigen::VectorXd& reaction_xy, const Vertex& a) const;
  // The distance to the obstacle at time t of the full field U_full on W^h.
  double gap(const Eigen::VectorXd& U_full, const Vertex& a, double t = 0.0) const;
  // Σ_a F_N(a), the total contact force.
  double total_force(const Eigen::VectorXd& reaction_xy) const;

 private:
  const ConstrainedProblem& p_;
  std::vector<Vertex> vertices_;
};

// The largest penetration of the whole boundary into the obstacles at time t:
// max(0, −min over the boundary vertices a and the obstacles k of φ_k(a + u(a), t)/
// |∇φ_k(a, 0)|) — also where no constraint acts (a part of the body that is not Γ_C).
// The scales |∇φ_k| are computed once.
class BoundaryPenetration {
 public:
  explicit BoundaryPenetration(const ConstrainedProblem& p);
  double operator()(const Eigen::VectorXd& U_full, double t) const;

 private:
  const ConstrainedProblem& p_;
  std::vector<int> vertices_;
  std::vector<std::vector<double>> scale_;  // [obstacle][vertex]
};

}  // namespace cdyn
