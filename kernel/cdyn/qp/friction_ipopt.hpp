// friction_ipopt.hpp — the frictional step problem (FQP) of qp/friction_qp.hpp by an
// interior-point method, Ipopt, on split slip variables (built with CDYN_WITH_IPOPT).
//
// The slip d = X_T − X̂_T of each contact node is split into its positive and negative
// parts, d = p − q with p, q ≥ 0, so that s|d| = s (p + q) at the minimum (one of the
// two vanishes where s > 0) and (FQP) for Tresca becomes a smooth convex QP
//
//     min ½ XᵀSX − rᵀX + Σ s (p + q)   subject to   X_T − p + q = X̂_T,  lower ≤ X ≤ upper,  p, q ≥ 0,
//
// Ipopt's own form (linear equalities, bounds; Hessian S in the X block, zero
// elsewhere).  Coulomb: a fixed point on the threshold, s = μ λ_N of the last Tresca
// solution, λ_N the reaction S X − r on the normal unknown.  As Ipopt's bound QP
// (qp/ipopt.hpp) an interior point ends near, not on, the sets: when friction_residual
// is above tol, a crossover by the semismooth Newton method (qp/friction_solvers.hpp,
// around pdas) from the sets of Ipopt's X finishes it.  One tangential unknown per node
// (the plane); explicit S only (InputError otherwise).
#pragma once

#include "cdyn/qp/friction_solvers.hpp"

namespace cdyn {

FrictionResult solve_friction_ipopt(BoundQP& qp, const FrictionConditions& f, const FrictionOptions& options,
                                    const FrictionResult* warm_start = nullptr);

}  // namespace cdyn
