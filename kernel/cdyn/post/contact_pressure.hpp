// contact_pressure.hpp — normal contact force, pressure and gap at the vertices of Γ_C
// against a rigid plane through p with unit normal n (problems/elastic_contact.hpp).
//
// The normal force on a constrained vertex a is F_N(a) = F(a)·n = −λ_N(a) ≥ 0, F the
// step's reaction at a in (x, y) (post/contact_force.hpp): a nodal force, the weak
// form's integral of the contact pressure against the vertex's hat function.  The
// pressure is p(a) = F_N(a) / w(a), w(a) = ∫_{Γ_C} φ_a ds the vertex's share of Γ_C (half
// the length of its contact edges: the P1 hat function on the boundary, whatever W^h
// is, since the constraint is nodal at the vertices), so that Σ_a F_N(a) = Σ_a p(a) w(a)
// is the total contact force.  The gap (a + u(a) − p)·n is the distance to the plane,
// negative where the body penetrates it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "cdyn/problems/constrained_problem.hpp"

namespace cdyn {

class ContactPressure {
 public:
  struct Vertex {
    int vertex;
    double s;       // coordinate along the plane, (a − p)·t, t = (−n_y, n_x)
    double weight;  // w(a) = ∫_{Γ_C} φ_a ds
  };

  // The constrained vertices of the contact parts (indices into mesh.part_names),
  // sorted by s.  n need not be normalized.
  ContactPressure(const ConstrainedProblem& p, const std::vector<int>& contact_parts, Point plane_point,
                  Point plane_normal);

  const std::vector<Vertex>& vertices() const { return vertices_; }
  const Point& normal() const { return n_; }

  // F_N(a) of a step's Cartesian reaction (post/contact_force.hpp's reaction_xy).
  double normal_force(const Eigen::VectorXd& reaction_xy, const Vertex& a) const;
  // p(a) = F_N(a) / w(a) (0 where w = 0).
  double pressure(const Eigen::VectorXd& reaction_xy, const Vertex& a) const;
  // (a + u(a) − p)·n for the full field U_full on W^h.
  double gap(const Eigen::VectorXd& U_full, const Vertex& a) const;
  // Σ_a F_N(a), the total contact force.
  double total_force(const Eigen::VectorXd& reaction_xy) const;

 private:
  const ConstrainedProblem& p_;
  Point point_, n_;
  std::vector<Vertex> vertices_;
};

}  // namespace cdyn
