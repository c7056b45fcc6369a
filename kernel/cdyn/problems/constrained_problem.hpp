// problems/constrained_problem.hpp — the semi-discrete constrained problem (seed eq. 16) on
// the free dofs of W^h, ready for a time scheme:
//
//     M Ü + A U = L(t) + Gᵀλ,   G U ≤ α,  λ ≤ 0,  λᵀ(G U − α) = 0,
//
// with every constraint a bound on one unknown (lower ≤ U ≤ upper; G = −I on the
// obstacle dofs, so the seed's λ is minus the QP reaction).  The problem also keeps
// what is needed for the energy of the FULL field (Dirichlet dofs included):
//     J = ½ Vᵀ C V + ½ Uᵀ A U − Lᵀ U    (seed, Theorem 2).
//
// Optional change of basis (elasticity against an inclined plane, problems/elastic_contact.hpp).
// A bound acts on ONE unknown, but the Signorini condition n·u(a) ≥ g(a) acts on a
// combination of u_x and u_y.  The problem may therefore carry an orthogonal,
// block-diagonal R on the free dofs (problems/nodal_rotation.hpp: 2 × 2 blocks [n t] at the contact
// nodes, identity elsewhere) and then its unknowns are the rotated components
//     U' = Rᵀ U_f    (normal n·u and tangential t·u at the contact nodes),
// with A = Rᵀ A_ff R, load = Rᵀ (L − A U_D)_f, the mass model seeing R
// (mass/rotated.hpp), and lower/upper/constrained naming rotated unknowns.  R is
// orthogonal, so J and every scheme's algebra are unchanged: the schemes use only A,
// load(t), mass, the bounds, full() and potential_energy(), and never know about R.
// Without R (the scalar problems, axis-aligned planes) U' = U_f and nothing changes.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/problems/rigid_obstacle.hpp"

namespace cdyn {

struct ConstrainedProblem {
  std::unique_ptr<FESpace> W;           // displacement space W^h
  std::unique_ptr<DirichletLift> bc;    // free/fixed dofs of W^h
  SparseMatrix A_full;                  // stiffness on all dofs of W^h
  std::function<Eigen::VectorXd(double)> L_full;  // load vector on all dofs at time t
  bool load_is_constant = true;         // L does not depend on t (then it is cached)
  Eigen::VectorXd UD;                   // Dirichlet lifting (constant in time)

  // Change of basis on the free dofs, U_f = R U' (absent: the identity).
  std::optional<SparseMatrix> R;

  SparseMatrix A;                       // A_ff (Rᵀ A_ff R with a rotation)
  std::unique_ptr<MassModel> mass;      // M = Bᵀ C⁻¹ B on the free dofs (Rᵀ M R)
  Eigen::VectorXd lower, upper;         // the constraint set K̄^h as bounds at t = 0 (±inf: none)
  std::vector<int> constrained;         // free dofs carrying a finite bound

  // K̄^h(t) for an obstacle that moves (a datum g(x, t) of the bounds): writes the bounds
  // at time t into lower, upper (sized n_free()).  Empty: the bounds are constant.
  std::function<void(double t, Eigen::VectorXd& lower, Eigen::VectorXd& upper)> moving_bounds;

  // The contact vertices of an elastic contact problem, each with the obstacle that
  // constrains it, the obstacle's unit outward normal there and |∇φ| (so that
  // φ(x, t)/scale is the distance to the obstacle near the vertex), and the obstacles
  // (problems/rigid_obstacle.hpp).  Empty for the scalar problems.
  struct ContactNode {
    int vertex = -1, obstacle = 0;
    Point normal;
    double scale = 1.0;
  };
  std::vector<ContactNode> contact_nodes;
  std::vector<RigidObstacle> obstacles;
  // The contact vertices with friction (problems/friction.hpp), each with its normal and
  // tangential unknowns (rotated even against an axis-aligned plane); empty without.
  std::vector<FrictionNode> friction;

  int n_free() const { return static_cast<int>(A.rows()); }

  // (L(t) − A U_D)_f: the load seen by the free dofs (Rᵀ (L(t) − A U_D)_f).  A
  // reference to the cache of the last three times asked (a step needs L at tⁿ, t^{n+½}
  // and t^{n+1}: the scheme's level and the data's work): valid until load() or
  // full_load() has been called with three other times.
  const Eigen::VectorXd& load(double t) const;

  // The full coefficient vector P R U' + U_D (R U' = U' without a rotation).
  Eigen::VectorXd full(const Eigen::VectorXd& Uf) const;

  // Unknowns ↔ Cartesian components of the free dofs: global(X') = R X',
  // local(X) = Rᵀ X (both the identity without a rotation).  local() of a Cartesian
  // free vector gives its normal (and tangential) components at the contact nodes, so
  // it is also how a reaction or a displacement is reported in the contact frame;
  // global() brings the unknowns, or a reaction Gᵀλ of a step, back to (x, y).
  Eigen::VectorXd global(const Eigen::VectorXd& X) const;
  Eigen::VectorXd local(const Eigen::VectorXd& X) const;

  // The unknowns of a full coefficient vector (e.g. an interpolated initial
  // displacement or velocity): Rᵀ (U)_f.  Use it instead of bc->restrict() so that a
  // rotated problem gets rotated initial data.
  Eigen::VectorXd unknowns(const Eigen::VectorXd& U_full) const { return local(bc->restrict(U_full)); }

  // L(t) on all dofs (assembled once when the load is constant, else once per t; the
  // same cache as load()).
  const Eigen::VectorXd& full_load(double t) const;

  // ½ UᵀAU − LᵀU of the full field at time t.
  double potential_energy(const Eigen::VectorXd& Uf, double t) const;

  bool bounds_are_constant() const { return !moving_bounds; }
  // The bounds at time t (lower, upper themselves when they are constant).
  void bounds(double t, Eigen::VectorXd& lower_t, Eigen::VectorXd& upper_t) const;

  // Largest violation max(lower − U, U − upper, 0) over the constrained dofs, against
  // the bounds at time t.
  double max_violation(const Eigen::VectorXd& Uf, double t = 0.0) const;

 private:
  struct CachedLoad {
    double t = 0.0;
    Eigen::VectorXd full, free;  // L(t) and (L(t) − A U_D)_f
  };
  const CachedLoad& cached_load(double t) const;
  mutable std::array<CachedLoad, 3> load_cache_;
  mutable int load_cache_size_ = 0, load_cache_next_ = 0;
  mutable Eigen::VectorXd lift_force_;  // (A U_D)_f, made by the first load() (A_full, U_D fixed by then)
};

// The unknowns of each cell's bubble when W^h = P1+, one per component (free ones only):
// the blocks the step's static condensation may eliminate together (qp/condensation.hpp;
// in elasticity no single one of them can be).  Empty for the other spaces.
std::vector<std::vector<int>> bubble_unknowns(const ConstrainedProblem& p);

}  // namespace cdyn
