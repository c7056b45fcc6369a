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

// The part of v (a vector on the free unknowns in the nodal frames: the reaction, or
// State::slip) on the friction nodes' tangential unknowns, in x, y, z: p.global() of v
// with every other entry set to 0 (empty stays empty: before the first step).  At a
// friction vertex it is the tangential force λ_T, or the slip, as a vector, whose length
// is tangential_magnitude's in space (problems/friction.hpp) — also on a roller, whose
// fixed component carries part of the normal force.
Eigen::VectorXd tangential_xy(const ConstrainedProblem& p, const Eigen::VectorXd& v);

}  // namespace cdyn
