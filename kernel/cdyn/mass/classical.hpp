// classical.hpp — the classical mass models, V = U̇ in W^h (mass/mass_model.hpp):
//
//   consistent     M = M_ff = ρ ∫φ_iφ_j restricted to the free dofs;
//   lumped         M = diag(ρ M_full 1_h) on the free dofs (row sums: 1_h = 1 for the
//                  nodal P1/P2 bases; the hierarchical P1+ basis gets ∫φ_i on the vertex
//                  rows and ∫b on its bubbles);
//   redistributed  M = Tᵀ M_ff T, no inertia on the contact dofs (Khenous–Laborde–Renard;
//                  T in mass/redistribution.hpp).
//
// Each gives matrix() = M, momentum(V) = M V, velocity(U̇) = U̇, ½ VᵀMV, and the saddle
// form {A, B_s, C_s, k} with B_sᵀ C_s⁻¹ B_s = M and C_s positive definite: (M, M) for
// consistent and lumped, (M_ff T, M_ff) for redistributed (its M is singular).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cdyn/mass/mass_model.hpp"

namespace cdyn {

// model: Consistent, Lumped or Redistributed; contact_free_dofs only for the last.
std::unique_ptr<MassModel> make_classical_mass_model(const FESpace& W, const DirichletLift& bc,
                                                     MassSpec::Model model, const CellCoefficient& rho,
                                                     const std::vector<int>& contact_free_dofs);

}  // namespace cdyn
