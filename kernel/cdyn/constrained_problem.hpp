// constrained_problem.hpp — the semi-discrete constrained problem (seed eq. 16) on
// the free dofs of W^h, ready for a time scheme:
//
//     M Ü + A U = L(t) + Gᵀλ,   G U ≤ α,  λ ≤ 0,  λᵀ(G U − α) = 0,
//
// with every constraint a bound on one unknown (lower ≤ U ≤ upper; G = −I on the
// obstacle dofs, so the seed's λ is minus the QP reaction).  The problem also keeps
// what is needed for the energy of the FULL field (Dirichlet dofs included):
//     J = ½ Vᵀ C V + ½ Uᵀ A U − Lᵀ U    (seed, Theorem 2).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "cdyn/dirichlet.hpp"
#include "cdyn/mass_model.hpp"

namespace cdyn {

struct ConstrainedProblem {
  std::unique_ptr<FESpace> W;           // displacement space W^h
  std::unique_ptr<DirichletLift> bc;    // free/fixed dofs of W^h
  SparseMatrix A_full;                  // stiffness on all dofs of W^h
  std::function<Eigen::VectorXd(double)> L_full;  // load vector on all dofs at time t
  bool load_is_constant = true;         // L does not depend on t (then it is cached)
  Eigen::VectorXd UD;                   // Dirichlet lifting (constant in time)

  SparseMatrix A;                       // A_ff
  std::unique_ptr<MassModel> mass;      // M = Bᵀ C⁻¹ B on the free dofs
  Eigen::VectorXd lower, upper;         // the constraint set K̄^h as bounds (±inf: none)
  std::vector<int> constrained;         // free dofs carrying a finite bound

  int n_free() const { return static_cast<int>(A.rows()); }

  // (L(t) − A U_D)_f: the load seen by the free dofs.
  Eigen::VectorXd load(double t) const;

  // The full coefficient vector P U_f + U_D.
  Eigen::VectorXd full(const Eigen::VectorXd& Uf) const { return bc->extend(Uf, UD); }

  // L(t) on all dofs (assembled once when the load is constant, else once per t).
  const Eigen::VectorXd& full_load(double t) const;

  // ½ UᵀAU − LᵀU of the full field at time t.
  double potential_energy(const Eigen::VectorXd& Uf, double t) const;

  // Largest violation max(lower − U, U − upper, 0) over the constrained dofs.
  double max_violation(const Eigen::VectorXd& Uf) const;

 private:
  mutable double cached_t_ = 0.0;
  mutable Eigen::VectorXd cached_full_load_, cached_load_;
};

}  // namespace cdyn
