// problems/friction.hpp — nodal friction at the contact vertices of an elastic body
// against a rigid obstacle (the seed: "for a particular choice of the discretization of
// Λ_N, one can obtain a nodal contact and friction condition").
//
// At a contact vertex a with normal n and tangent t (problems/nodal_rotation.hpp) the
// nodal contact force is λ_N n + λ_T t (λ_N ≥ 0 the QP reaction on the normal unknown,
// docs/elasticity.md §2), and the friction law bounds the tangential part:
//
//     Tresca:   |λ_T| ≤ s_a,       s_a = ∫_{Γ_C} s φ_a dΓ    (s a given bound on the shear traction)
//     Coulomb:  |λ_T| ≤ μ(a) λ_N
//
// with λ_T = −s_a u̇_T/|u̇_T| where the vertex slips (u̇_T ≠ 0): the maximal dissipation
// law.  The nodal threshold s_a is the traction bound integrated against the vertex's
// basis function on Γ_C (its share of the contact boundary, as the contact pressure of
// post/contact_pressure.hpp is the nodal force divided by it).  Tresca acts at every
// contact vertex whether it touches or not (a given threshold is the model); Coulomb
// vanishes with λ_N.  The time-discrete form, on the slip of a step, is qp/friction_qp.hpp.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "cdyn/fe/field.hpp"

namespace cdyn {

enum class FrictionLaw { None, Tresca, Coulomb };

// "none", "tresca", "coulomb"; InputError (parameter "friction") for anything else.
FrictionLaw parse_friction_law(const std::string& name);
std::string to_string(FrictionLaw law);

// The friction of one obstacle: the law, μ(x) (Coulomb, ≥ 0) and s(x) (Tresca, a
// traction ≥ 0; +∞ allowed: the bonded tangential condition).  Both taken at t = 0.
struct FrictionSpec {
  FrictionLaw law = FrictionLaw::None;
  Field mu = [](const Point&, double) { return 0.0; };
  Field threshold = [](const Point&, double) { return 0.0; };
};

// One contact vertex with friction, on the problem's unknowns: its normal unknown (the
// bounded one), its tangential unknowns (one in the plane; a list so that space can
// follow with t₁, t₂), and its law with the nodal coefficient.
struct FrictionNode {
  int node = -1;                 // into ConstrainedProblem::contact_nodes
  int normal = -1;
  std::vector<int> tangential;
  FrictionLaw law = FrictionLaw::None;
  double mu = 0.0;               // Coulomb: μ(a)
  double threshold = 0.0;        // Tresca: s_a = ∫_{Γ_C} s φ_a
};

// The tangential part of v (a vector on the free unknowns: the reaction λ = S X − r,
// which gives the friction force λ_T, or State::slip) at a friction node: in the plane
// the signed value on its tangential unknown, in space its length in the tangent plane.
double tangential_magnitude(const FrictionNode& node, const Eigen::VectorXd& v);

}  // namespace cdyn
