// problems/scalar_wave.cpp — assembling the membrane / bar problem on the free dofs.
#include "cdyn/problems/scalar_wave.hpp"

#include <limits>

#include "cdyn/base/error.hpp"

namespace cdyn {

ConstrainedProblem build_scalar_wave(const Mesh& mesh, const ScalarWaveData& d) {
  if (!(d.rho > 0.0)) throw InputError("rho", "must be positive");
  if (!(d.kappa > 0.0)) throw InputError("kappa", "the stiffness (E or the tension) must be positive");
  ConstrainedProblem p;
  p.W = std::make_unique<FESpace>(mesh, d.mass.W);
  const FESpace& W = *p.W;
  p.bc = std::make_unique<DirichletLift>(W, d.dirichlet_parts);
  p.A_full = d.kappa * assemble_laplace(W);
  p.L_full = load_in_time(W, {d.f}, !d.load_is_constant);
  p.load_is_constant = d.load_is_constant;
  p.UD = d.dirichlet_parts.empty() ? Eigen::VectorXd::Zero(W.n_dofs()) : p.bc->lifting(W, {d.dirichlet_value});
  p.A = p.bc->restrict(p.A_full);

  // K̄^h: u(a_i) ≥ g(a_i) at the free vertex dofs (never at bubble or edge dofs).
  // The constrained dofs are found even when the obstacle is disabled: the
  // redistributed mass depends on them, and the unconstrained run must keep the same M.
  const double inf = std::numeric_limits<double>::infinity();
  p.lower = Eigen::VectorXd::Constant(p.n_free(), -inf);
  p.upper = Eigen::VectorXd::Constant(p.n_free(), inf);
  std::vector<int> vertices;
  if (d.obstacle_on_all_vertices) {
    for (int v = 0; v < mesh.n_vertices(); ++v) vertices.push_back(v);
  } else {
    vertices = mesh.part_vertices(d.obstacle_parts);
  }
  std::vector<int> contact, constrained_vertex;
  for (int v : vertices) {
    const int i = p.bc->free_index(W.vertex_dof(v));
    if (i < 0) continue;  // a Dirichlet vertex is not constrained
    contact.push_back(i);
    if (!d.obstacle) continue;
    const Point& a = mesh.vertices[v];
    p.lower[i] = d.obstacle_g(a, 0.0);
    p.constrained.push_back(i);
    constrained_vertex.push_back(v);
  }
  if (d.obstacle && d.obstacle_moves) {
    // K̄^h(t): u(a_i) ≥ g(a_i, t), at the time level each scheme constrains.
    const std::vector<int> index = p.constrained;
    const Field g = d.obstacle_g;
    p.moving_bounds = [&mesh, index, constrained_vertex, g](double t, Eigen::VectorXd& lower, Eigen::VectorXd&) {
      for (std::size_t k = 0; k < index.size(); ++k) lower[index[k]] = g(mesh.vertices[constrained_vertex[k]], t);
    };
  }
  p.mass = make_mass_model(W, *p.bc, d.mass, d.rho, contact);
  return p;
}

}  // namespace cdyn
