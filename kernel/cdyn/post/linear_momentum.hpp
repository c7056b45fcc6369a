// linear_momentum.hpp — the linear momentum of the free motion, ∫ ρ v_h.
//
// P_k = Σ_i (Bᵀ V)_i T_k,i with T_k the interpolated translation e_k (in W^h for P1, P1+
// and P2: its bubble and edge coefficients are those of a constant), i.e. ∫ ρ v_h·e_k of
// the velocity field (the classical models: Σ (M U̇)_i T_k,i).  Dirichlet dofs are left
// out: a clamped body's momentum is not conserved anyway.  Without contact and loads
// the schemes conserve it; with frictionless contact its change is the impulse of the
// contact force (an identity of the step, docs/elasticity.md).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "cdyn/problems/constrained_problem.hpp"

namespace cdyn {

class LinearMomentum {
 public:
  // Translations e_k for each component of W^h.
  explicit LinearMomentum(const ConstrainedProblem& p);
  // ∫ ρ v_h of a state's velocity V (components beyond W's are 0).
  Point operator()(const Eigen::VectorXd& V) const;

 private:
  const ConstrainedProblem& p_;
  std::vector<Eigen::VectorXd> T_;  // the translations on the free dofs (Cartesian)
};

}  // namespace cdyn
