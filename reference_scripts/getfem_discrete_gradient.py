#!/usr/bin/python3
"""getfem_discrete_gradient.py — the energy-exact discrete gradient scheme (docs/schemes.md)
on the clamped bar (docs/bar_impact.md §3, data/scenes/bar.toml), implemented
independently of cdyn: GetFEM's matrices, dense linear algebra, an orthonormal basis of
Ker B from scipy, and the energy correction β found by a bracketing root finder on the
corrected step (cdyn: a local basis of Ker B, secant and Muller steps).

    ρ u_tt − E u_xx = 0 on (0, 1), E = ρ = 1, u(1) = 0, u(0, t) ≥ 0,
    u(x, 0) = (1 − x)/2, u_t(x, 0) = 0.

-pair P1+/P0 (default): W^h = P1 plus a quadratic bubble per cell (GetFEM's
FEM_PK_HIERARCHICAL(1,2): the hat functions and one edge bubble), H^h = P0 (FEM_PK(1,0)).
-pair P2/P1: W^h = Lagrange P2 (FEM_PK(1,2)), H^h = P1 (FEM_PK(1,1)) without its dof at
the clamped end (as cdyn drops the velocity dofs of a Dirichlet boundary); cdyn solves
(14) there by the method of multipliers, this script by the same dense null space.
B_ij = ∫ψ_i φ_j, C_ij = ∫ψ_i ψ_j, A_ij = ∫φ_i' φ_j', exact integration.  One constraint,
W_0 ≥ 0 at x = 0.

  - Ψ(U): the potential ½WᵀAW of the solution W of min {½WᵀAW : B W = B U, W_0 ≥ 0}
    (the seed's eq. (14)), W = U + N d with N an orthonormal basis of Ker B
    (scipy.linalg.null_space); one inequality, solved in closed form (the unconstrained
    minimizer, or the one with W_0 = 0 by a Lagrange multiplier).
  - a step with correction β: X = U^{n+½} minimizes ½XᵀSX − r_βᵀX over X_0 ≥ 0 with
    S = 4c²M + A, r_β = 4c²M Uⁿ + 2c BᵀVⁿ − 2β M(X₀ − Uⁿ) (M = BᵀC⁻¹B, X₀ the step's
    solution at β = 0), one bound again; then U^{n+1} = W(2X − Uⁿ) by (14),
    V^{n+1} = 2c C⁻¹B(U^{n+1} − Uⁿ) − Vⁿ.
  - β: 0 when the step's energy change ΔH(0) is below 1e-13 of its terms; otherwise the
    root of ΔH(β) = ΔK + Ψ(U^{n+1}) − Ψ(Uⁿ) by scipy.optimize.brentq, bracketed by
    doubling away from 0, the root nearest 0; if no bracket exists within |β| < c²,
    two steps of dt/2 (recursively), as cdyn does.

    /usr/bin/python3 reference_scripts/getfem_discrete_gradient.py -n 40 -dt 0.0125 -steps 480 -out dg.csv [-pair P2/P1]
writes  step,t,E_total,u_contact.
"""
import argparse

import getfem as gf
import numpy as np
from scipy.linalg import null_space
from scipy.optimize import brentq


PAIRS = {"P1+/P0": ("FEM_PK_HIERARCHICAL(1,2)", "FEM_PK(1,0)"), "P2/P1": ("FEM_PK(1,2)", "FEM_PK(1,1)")}


def assemble(n, pair):
    m = gf.Mesh("cartesian", np.linspace(0.0, 1.0, n + 1))
    mw = gf.MeshFem(m, 1)
    mw.set_fem(gf.Fem(PAIRS[pair][0]))
    mh = gf.MeshFem(m, 1)
    mh.set_fem(gf.Fem(PAIRS[pair][1]))
    mim = gf.MeshIm(m, gf.Integ("IM_GAUSS1D(6)"))
    md = gf.Model("real")
    md.add_fem_variable("u", mw)
    md.add_fem_variable("v", mh)
    A = np.array(gf.asm("generic", mim, 2, "Grad_Test_u.Grad_Test2_u", -1, md).full())
    iu, nu = md.interval_of_variable("u")
    iv, nv = md.interval_of_variable("v")
    full = np.array(gf.asm("generic", mim, 2, "Test_v*Test2_u", -1, md).full())
    B = full[iv:iv + nv, iu:iu + nu]
    C = np.array(gf.asm("generic", mim, 2, "Test_v*Test2_v", -1, md).full())[iv:iv + nv, iv:iv + nv]
    A = A[iu:iu + nu, iu:iu + nu]
    x = mw.basic_dof_nodes()[0]
    vertex = [i for i in range(nu) if np.min(np.abs(x[i] - np.linspace(0.0, 1.0, n + 1))) < 1e-12]
    if pair == "P2/P1":  # the velocity vanishes at the clamped end: drop its H^h dof
        xh = mh.basic_dof_nodes()[0]
        keep = [i for i in range(nv) if abs(xh[i] - 1.0) > 1e-12]
        B, C = B[keep, :], C[np.ix_(keep, keep)]
    return A, B, C, x, vertex


def main():
    p = argparse.ArgumentParser()
    p.add_argument("-n", type=int, default=40)
    p.add_argument("-dt", type=float, default=0.0125)
    p.add_argument("-steps", type=int, default=480)
    p.add_argument("-out", default="getfem_discrete_gradient.csv")
    p.add_argument("-pair", default="P1+/P0", choices=sorted(PAIRS))
    a = p.parse_args()
    A, B, C, x, vertex = assemble(a.n, a.pair)
    # u(1) = 0: drop the vertex dof at x = 1 (the bubbles vanish there)
    clamped = [i for i in vertex if abs(x[i] - 1.0) < 1e-12]
    free = [i for i in range(len(x)) if i not in clamped]
    A, B = A[np.ix_(free, free)], B[:, free]
    x = x[free]
    vertex = [free.index(i) for i in vertex if i in free]
    contact = min(vertex, key=lambda i: abs(x[i]))
    Cinv = np.linalg.inv(C)
    M = B.T @ Cinv @ B
    N = null_space(B)  # orthonormal basis of Ker B
    e0 = np.zeros(len(x))
    e0[contact] = 1.0

    def min_one_bound(S, r):
        """argmin ½XᵀSX − rᵀX over X_contact ≥ 0 (S SPD)."""
        X = np.linalg.solve(S, r)
        if X[contact] >= 0.0:
            return X
        y = np.linalg.solve(S, e0)  # X = S⁻¹(r + μ e0) with X_contact = 0
        return X - (X[contact] / y[contact]) * y

    def reconstruct(U):
        """Eq. (14): W = U + N d minimizing ½WᵀAW with W_contact ≥ 0."""
        S = N.T @ A @ N
        r = -N.T @ (A @ U)
        d = np.linalg.solve(S, r)
        if U[contact] + N[contact] @ d < 0.0:  # active: add the multiplier of W_contact ≥ 0
            g = N[contact]
            y = np.linalg.solve(S, g)
            d = d - ((U[contact] + g @ d) / (g @ y)) * y
        return U + N @ d

    def psi(W):
        return 0.5 * W @ A @ W

    def attempt(U, V, h, beta, d=None):
        c = 1.0 / h
        r = 4 * c * c * M @ U + 2 * c * B.T @ V
        X = min_one_bound(4 * c * c * M + A, r if d is None else r - 2 * beta * d)
        D = X - U
        W1 = reconstruct(2 * X - U)
        kin_change = 8 * c * c * D @ M @ D - 4 * c * (B.T @ V) @ D
        terms = 0.5 * V @ C @ V + 8 * c * c * D @ M @ D + abs(4 * c * (B.T @ V) @ D) + psi(W1) + psi(U)
        return kin_change + psi(W1) - psi(U), terms, X, W1

    def step(U, V, h, depth=0):
        c = 1.0 / h
        dH, terms, X, W1 = attempt(U, V, h, 0.0)
        if abs(dH) > 1e-13 * terms:
            d = M @ (X - U)  # the uncorrected step's direction, fixed for the step
            f = lambda b: attempt(U, V, h, b, d)[0]  # noqa: E731
            bracket = None
            for sign in (1.0, -1.0):
                lo, width = 0.0, 1.0
                while width < c * c and bracket is None:
                    hi = sign * width
                    if f(lo) * f(hi) <= 0.0:
                        bracket = (min(lo, hi), max(lo, hi))
                    lo, width = hi, 2 * width
            if bracket is None:
                if depth >= 10:
                    raise RuntimeError("no energy correction even at dt/1024")
                U, V = step(U, V, h / 2, depth + 1)
                return step(U, V, h / 2, depth + 1)
            beta = brentq(f, *bracket, xtol=1e-14, rtol=1e-15)
            _, _, X, W1 = attempt(U, V, h, beta, d)
        V1 = 2 * c * (Cinv @ (B @ (W1 - U))) - V
        return W1, V1

    # u₀ = (1 − x)/2: in the hierarchical basis the vertex values, bubbles 0; in the
    # Lagrange P2 basis the values at every node (u₀ is affine); its Ker B part from (14)
    at_node = np.zeros(len(x))
    at_node[vertex if a.pair == "P1+/P0" else slice(None)] = 1.0
    U = reconstruct(at_node * (1.0 - x) / 2.0)
    V = np.zeros(B.shape[0])

    def energy():
        return 0.5 * V @ C @ V + psi(U)

    with open(a.out, "w") as f:
        f.write("step,t,E_total,u_contact\n")
        f.write(f"0,0,{energy():.17g},{U[contact]:.17g}\n")
        for n in range(1, a.steps + 1):
            U, V = step(U, V, a.dt)
            f.write(f"{n},{n * a.dt:.17g},{energy():.17g},{U[contact]:.17g}\n")


if __name__ == "__main__":
    main()
