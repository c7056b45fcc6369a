// contact_force.hpp — the constraint force of a step, vertex by vertex, in the
// coordinates of the mesh.
//
// A step's QP reaction Gᵀλ (State::reaction) is a force on the problem's unknowns:
// the free dofs of W^h, rotated to normal and tangential components at the contact
// nodes of an inclined plane (problems/nodal_rotation.hpp).  Post-processing wants it in
// (x, y): reaction_xy() turns it back once (ConstrainedProblem::global), and every
// function below reads that Cartesian form.
//
// The seed's multiplier (eq. 16: λ ≤ 0, G = −I for the obstacle u ≥ g) is minus the
// reaction where a vertex carries a constraint; for Signorini contact against a rigid
// plane of normal n it is the vector λ_N n with λ_N = −F·n ≤ 0 (problems/elastic_contact.hpp).
#pragma once

#include <Eigen/Core>

#include "cdyn/problems/constrained_problem.hpp"

namespace cdyn {

// The reaction in Cartesian components of the free dofs: R · reaction with a rotation,
// the reaction itself without (empty stays empty: before the first step).
Eigen::VectorXd reaction_xy(const ConstrainedProblem& p, const Eigen::VectorXd& reaction);

// The force on a vertex (0 on fixed components, and everywhere before the first step).
Point vertex_force(const ConstrainedProblem& p, const Eigen::VectorXd& reaction_xy, int vertex);

// Whether some component of the vertex carries a finite bound.
bool is_constrained_vertex(const ConstrainedProblem& p, int vertex);

// The seed's multiplier at a vertex as a vector: −vertex_force where the vertex is
// constrained, 0 elsewhere.  At an inactive constraint it is the QP's residual, zero up
// to round-off (~1e-14), so λ ≤ 0 holds to that.
Point vertex_multiplier(const ConstrainedProblem& p, const Eigen::VectorXd& reaction_xy, int vertex);

// Friction node k's tangential force λ_T (the reaction less its part along the node's
// normal n) and slip (State::slip, whose normal part is 0) as vectors in x, y, z, from
// reaction_xy and slip_xy = p.global(State::slip); zero before the first step (empty
// vectors).  Their lengths are tangential_magnitude's in space (problems/friction.hpp).
struct TangentialVectors {
  Point force, slip;
};
TangentialVectors tangential_vectors(const ConstrainedProblem& p, const Eigen::VectorXd& reaction_xy,
                                     const Eigen::VectorXd& slip_xy, int k);

}  // namespace cdyn
