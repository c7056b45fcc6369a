// mass/mass_model.hpp — the inertia of the semi-discrete problem (seed eqs. 10–11).
//
// The seed's class of approximations carries the velocity in its own space H^h:
//     C V = B U̇,   M = Bᵀ C⁻¹ B,   kinetic energy ½ Vᵀ C V  (= ½ U̇ᵀ M U̇),
// with B_ij = ∫ψ_i φ_j and C_ij = ∫ψ_i ψ_j (fe/assembly.hpp).  The classical mass models
// (consistent, lumped, redistributed) are the special case V = U̇ in W^h, where B and
// C are replaced by the chosen M itself: C V = B U̇ reads M (V − U̇) = 0, and V = U̇.
//
// Everything here acts on the FREE dofs of W^h (Dirichlet dofs eliminated, see
// fe/dirichlet.hpp): the velocity of a fixed dof is the rate of its data, which the
// kinetic energy of the free motion does not see (the Dirichlet data of the seed's
// experiments are constant in time).
//
// The time schemes only ever need the four operations below, which is what lets
// one scheme serve every pair and every mass model.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "cdyn/base/sparse.hpp"
#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/mass/mass_spec.hpp"

namespace cdyn {

class MassModel {
 public:
  virtual ~MassModel() = default;

  // "P1+/P0", "consistent", ... (MassSpec::name()).
  virtual std::string name() const = 0;

  // Whether M is invertible (no massless displacement: Ker M = Ker B = {0}).  The
  // pairs with N_H < N_W and the redistributed mass are not; a pair with N_H ≥ N_W is
  // when B has full column rank (checked once, on the first call).
  virtual bool is_invertible() const = 0;

  // Whether the velocity is the displacement rate itself, V = U̇ in W^h (the classical
  // models: H^h = W^h with C = B = M), as the explicit schemes need.
  virtual bool velocity_is_rate() const = 0;

  // Number of velocity unknowns N_H (free dofs of W^h for the classical models).
  virtual int n_velocity() const = 0;

  // M = Bᵀ C⁻¹ B as a sparse matrix, when that is cheap and sparse: H^h = P0 (C is
  // diagonal) and the classical models.  Empty for continuous H^h (C⁻¹ is dense).
  virtual std::optional<SparseMatrix> matrix() const = 0;

  // S = A + k M in the sparse saddle form [[A, k Bᵀ], [B, −C]] (qp/bound_qp.hpp), for the
  // models without a sparse M.
  virtual SaddleForm saddle(const SparseMatrix& A, double k) const = 0;

  // Bᵀ V: the momentum of the velocity V as a force on W^h (= M V for classical models).
  virtual Eigen::VectorXd momentum(const Eigen::VectorXd& V) const = 0;

  // C⁻¹ B Ẇ: the velocity in H^h of a displacement rate Ẇ (= Ẇ for classical models).
  virtual Eigen::VectorXd velocity(const Eigen::VectorXd& Wdot) const = 0;

  // ½ Vᵀ C V.
  virtual double kinetic_energy(const Eigen::VectorXd& V) const = 0;

  // The acceleration in H^h of a force F: A with Bᵀ A = F (the inertia force of seed
  // eq. 16 is M Ü = Bᵀ A) that is the rate of a velocity, A = C⁻¹ B a for some a in
  // W^h.  A least squares solution when F is not in the range of M (a singular M whose
  // massless modes are not in equilibrium); M Ü = F exactly otherwise.  One sparse QR
  // factorization per call: meant for starting a scheme, not for every step.
  virtual Eigen::VectorXd acceleration(const Eigen::VectorXd& F) const = 0;
};

}  // namespace cdyn

// ----- construction (mass/mass_model.cpp, mixed.cpp, classical.cpp) ---------------
// See docs/semi_discretization.md for the construction of each M.

#include <vector>

namespace cdyn {

// The mass model `spec` on the free dofs of W^h (Dirichlet dofs of `bc` eliminated),
// with density ρ (spec.W must be W's element).  ρ is one number or one value per cell
// (fe/cell_coefficient.hpp: a body of several materials); every "ρ ∫" below is then
// ∫ ρ, cell by cell, and the single-material matrices are bit for bit unchanged:
//
//  - a pair W^h/H^h (seed eqs. 10–11), H^h with as many components as W^h.  B and C are
//    assembled with ρ (ρB, ρC), so that M = ρ Bᵀ C⁻¹ B, V = C⁻¹ B U̇ does not depend on
//    a uniform ρ and the kinetic energy is ½ Vᵀ (ρC) V.  (With H^h = P0 a per-cell ρ
//    scales the rows of B and C of each cell alike, so V = C⁻¹ B U̇ is still the cell
//    mean of U̇; with a continuous H^h, V is the ρ-weighted L² projection of U̇.)  A continuous H^h takes the Dirichlet
//    conditions of W^h: its dofs at the fixed vertices (and, for H^h = W^h, every fixed
//    dof) are removed, so the velocity vanishes where the displacement is prescribed and
//    P1/P1 is exactly the consistent mass M_ff.  H^h = P2 needs W^h = P2 (its edge dofs
//    are identified through W).
//  - consistent: M_ff = ρ ∫φ_iφ_j on the free dofs;
//  - lumped: row-sum lumping, M = diag(ρ M_full 1_h) on the free dofs (1_h the
//    interpolant of the constant 1: the row sums for P1 and P2); InputError if a
//    diagonal entry is not positive (2D P2, whose vertex rows sum to zero);
//  - redistributed: M = Tᵀ M_ff T (mass/redistribution.hpp), no inertia on
//    `contact_free_dofs` (indices among the free dofs, vertex dofs only), total mass,
//    centre of mass and second moments of M_ff kept exactly.  For a vector space give
//    the contact dofs you want massless: both components of each contact node (then
//    every normal N_i is in Ker M; the recommended choice) or only the one component
//    the constraint acts on (an axis-aligned normal).
// `contact_free_dofs` is ignored by every other model.  Throws InputError (parameter
// "rho" for ρ ≤ 0 on some cell, "pair" for a pair W's mesh cannot carry, a spec whose W is not W's
// element, or a redistribution with no donors).
std::unique_ptr<MassModel> make_mass_model(const FESpace& W, const DirichletLift& bc, const MassSpec& spec,
                                           const CellCoefficient& rho, const std::vector<int>& contact_free_dofs = {});

// The same with the spec in text form (MassSpec::parse with W's element).
std::unique_ptr<MassModel> make_mass_model(const FESpace& W, const DirichletLift& bc, const std::string& spec,
                                           const CellCoefficient& rho, const std::vector<int>& contact_free_dofs = {});

// The blocks of the pair W^h/H^h on the free dofs: B (N_H × n_free) and C (N_H × N_H),
// both multiplied by ρ; the H^h dofs removed by the Dirichlet conditions (see
// make_mass_model) are listed in `velocity_fixed`.  `velocity_dirichlet = false` keeps
// every dof of a continuous H^h (the alternative discussed in the docs; make_mass_model
// always uses true).
struct MixedBlocks {
  SparseMatrix B, C;
  int n_velocity_full = 0;           // dofs of H^h before elimination
  std::vector<int> velocity_fixed;   // eliminated dofs of H^h
};
MixedBlocks mixed_blocks(const FESpace& W, const DirichletLift& bc, Element H, const CellCoefficient& rho,
                         bool velocity_dirichlet = true);

// M as a sparse matrix whenever it is one: matrix() (H^h = P0, the classical models),
// or C when B = C (H^h = W^h: M = Bᵀ C⁻¹ B = C, the consistent mass); empty when C⁻¹
// is dense (P1+/P1, P2/P1: the step QP is then in saddle form).
std::optional<SparseMatrix> sparse_mass(const MassModel& mass);

}  // namespace cdyn
