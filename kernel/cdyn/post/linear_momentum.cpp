// linear_momentum.cpp — ∫ ρ v_h through the momentum Bᵀ V of the mass model.
#include "cdyn/post/linear_momentum.hpp"

namespace cdyn {

LinearMomentum::LinearMomentum(const ConstrainedProblem& p) : p_(p) {
  const int nc = p.W->components();
  for (int k = 0; k < nc; ++k) {
    std::vector<Field> e(nc, [](const Point&, double) { return 0.0; });
    e[k] = [](const Point&, double) { return 1.0; };
    T_.push_back(p.bc->restrict(p.W->interpolate(e)));
  }
}

Point LinearMomentum::operator()(const Eigen::VectorXd& V) const {
  const Eigen::VectorXd BtV = p_.global(p_.mass->momentum(V));  // Cartesian free components
  double P[3] = {0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < T_.size(); ++k) P[k] = BtV.dot(T_[k]);
  return {P[0], P[1], P[2]};
}

}  // namespace cdyn
