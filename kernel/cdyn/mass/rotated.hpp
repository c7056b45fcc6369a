// rotated.hpp — a mass model seen through an orthogonal change of basis of W^h's
// free dofs, U = R U' (problems/constrained_problem.hpp; R from problems/nodal_rotation.hpp, Rᵀ R = I).
//
// A pair W^h/H^h: only the displacement side of seed eq. 10 turns, H^h does not.
// Substituting U = R U' in  C V = B U̇  and  M = Bᵀ C⁻¹ B  gives
//     B' = B R,   C' = C,   M' = B'ᵀ C⁻¹ B' = Rᵀ M R,
// so the operations of mass/mass_model.hpp become
//     momentum(V)      = B'ᵀ V     = Rᵀ (Bᵀ V)
//     velocity(Ẇ')     = C⁻¹ B' Ẇ' = inner velocity of R Ẇ'
//     matrix()         = Rᵀ M R                       (when M is explicit)
//     saddle(A', k)    = {A', B_s R, C_s, k}           (B_s, C_s the inner factors)
//     acceleration(F') = inner acceleration of R F'    (B'ᵀ a = Rᵀ Bᵀ a = Rᵀ R F' = F')
// and the kinetic energy ½ Vᵀ C V is unchanged: V lives in H^h.
//
// A classical model (consistent, lumped, redistributed) has H^h = W^h and V = U̇
// (mass/mass_model.hpp), which the explicit schemes rely on (Paoli–Schatzman sets
// V = (U^{n+1} − Uⁿ)/dt in the problem's unknowns).  There H^h turns with W^h: V' = Rᵀ V,
//     momentum(V') = Rᵀ M R V',  velocity(Ẇ') = Ẇ',  ½ V'ᵀ Rᵀ M R V' = ½ Vᵀ M V,
//     acceleration(F') = Rᵀ M⁻¹ R F',
// which is the same model written in the rotated basis.  Either way J is unchanged.
#pragma once

#include <memory>

#include "cdyn/mass/mass_model.hpp"

namespace cdyn {

// The model `inner` (on the Cartesian free dofs) seen from the unknowns U' = Rᵀ U.
// R must be orthogonal and square of the size of inner's displacement side.
std::unique_ptr<MassModel> make_rotated_mass_model(std::unique_ptr<MassModel> inner, SparseMatrix R);

}  // namespace cdyn
