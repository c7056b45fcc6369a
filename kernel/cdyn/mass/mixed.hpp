// mixed.hpp — the seed's pairs W^h/H^h as mass models (seed eqs. 10–11):
//
//     C V = B U̇,   M = Bᵀ C⁻¹ B,   kinetic energy ½ Vᵀ C V,
//
// B and C from mixed_blocks() (mass/mass_model.hpp): free columns of W^h, the H^h dofs left
// by the Dirichlet conditions, both scaled by ρ.
//  - H^h = P0: C is diagonal (the cell measures), M = Bᵀ C⁻¹ B is sparse (its pattern
//    is the cell–cell coupling of W^h) and matrix() returns it;
//  - H^h continuous (P1, ...): C⁻¹ is dense, matrix() is empty, S = A + k M is given
//    by its saddle form {A, B, C, k}; velocity() solves with a Cholesky factor of C
//    (CHOLMOD, analysed and factorized once).  For H^h = W^h (P1/P1) B = C, so
//    velocity() is the identity and M = C (schemes/step_qp_scheme.cpp then builds S explicitly).
#pragma once

#include <memory>

#include "cdyn/mass/mass_model.hpp"

namespace cdyn {

// The pair W.element()/H on W's free dofs.  Throws InputError if W is not continuous
// or H = P2 with W ≠ P2.
std::unique_ptr<MassModel> make_mixed_mass_model(const FESpace& W, const DirichletLift& bc, Element H,
                                                 const CellCoefficient& rho);

}  // namespace cdyn
