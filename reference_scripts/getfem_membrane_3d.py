#!/usr/bin/python3
"""getfem_membrane_3d.py — the scalar wave with an obstacle on the unit cube
(data/scenes/membrane_3d.toml) integrated step by step with GetFEM's tetrahedral elements
and scipy: an independent reference for cdyn's 3D pairs and schemes (tests/reference,
docs/three_d.md).

    u_tt − Δu = f = −0.6 in (0, 1)³, u = 0.02 on the six faces, u(a) ≥ g(a) = 0.01 − 0.04 z
    at every vertex a, u(0) = 0.02 + 0.02 sin(πx) sin(πy) sin(πz), u_t(0) = 0.

Mesh: cdyn's unit_cube (n³ cells of six tetrahedra, getfem_matrices.cube_mesh).  Pairs
(seed eqs. 10–11): P1/P1 (FEM_PK(3,1) twice; the velocity dofs of the faces dropped,
as cdyn drops those of a Dirichlet boundary) and P1+/P0 (FEM_PK_WITH_CUBIC_BUBBLE(3,1),
P1 plus the quartic bubble, and FEM_PK_DISCONTINUOUS(3,0)); B_ij = ∫ψ_i φ_j,
C_ij = ∫ψ_i ψ_j, A_ij = ∫∇φ_i·∇φ_j, L_i = ∫f φ_i with IM_TETRAHEDRON(8) (exact for every
product here), M = Bᵀ C⁻¹ B.  The initial state interpolates u(0) at the vertices and,
for P1+, at each cell's centroid (cdyn's interpolant), whatever GetFEM's basis.

Schemes (docs/schemes.md), c = 1/dt:
  backward_euler: X = U^{n+1}, S = c² M + A, r = c² M Uⁿ + c Bᵀ Vⁿ + L,
                  V^{n+1} = c C⁻¹B (U^{n+1} − Uⁿ);
  midpoint:       X = U^{n+½}, S = 4c² M + A, r = 4c² M Uⁿ + 2c Bᵀ Vⁿ + L,
                  U^{n+1} = 2X − Uⁿ, V^{n+1} = 2c C⁻¹B (U^{n+1} − Uⁿ) − Vⁿ
                  (the full step extrapolated: cdyn with time.reconstruct = false).
Each step minimizes ½XᵀSX − rᵀX with the face dofs fixed and X ≥ g at the free
vertices, by a primal-dual active set loop on scipy's sparse LU (SuperLU) of the
inactive block, started from the previous step's active set; a step ends only when
its KKT conditions hold to 1e-12 (X ≥ g, multiplier ≥ 0, complementarity), else the
script stops.

    /usr/bin/python3 reference_scripts/getfem_membrane_3d.py -pair P1+/P0 -scheme midpoint -n 8 -dt 0.002 -steps 400 -out m3.csv
writes  step,t,E_kin,E_pot,E_total,u_centre,u_low,active  (E_kin = ½VᵀCV,
E_pot = ½UᵀAU − LᵀU on the whole field, u at (½, ½, ½) and (½, ½, ⅛), active: the
vertex constraints held at the step's solution).
"""
import argparse
import math

import getfem as gf
import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from getfem_matrices import cube_mesh

PAIRS = {"P1/P1": ("FEM_PK(3,1)", "FEM_PK(3,1)"),
         "P1+/P0": ("FEM_PK_WITH_CUBIC_BUBBLE(3,1)", "FEM_PK_DISCONTINUOUS(3,0)")}


def u0(p):
    x, y, z = p
    return 0.02 + 0.02 * math.sin(math.pi * x) * math.sin(math.pi * y) * math.sin(math.pi * z)


def scipy_matrix(M):
    """A GetFEM Spmat as a scipy CSC matrix."""
    jc, ir = M.csc_ind()
    n_rows, n_cols = M.size()
    return sp.csc_matrix((M.csc_val(), ir, jc), shape=(n_rows, n_cols))


def assemble(mesh, pair):
    mim = gf.MeshIm(mesh, gf.Integ("IM_TETRAHEDRON(8)"))
    mfw, mfh = gf.MeshFem(mesh, 1), gf.MeshFem(mesh, 1)
    mfw.set_fem(gf.Fem(PAIRS[pair][0]))
    mfh.set_fem(gf.Fem(PAIRS[pair][1]))
    md = gf.Model("real")
    md.add_fem_variable("u", mfw)
    md.add_fem_variable("v", mfh)
    iu, nu = md.interval_of_variable("u")
    iv, nv = md.interval_of_variable("v")
    whole = lambda expr: scipy_matrix(gf.asm("generic", mim, 2, expr, -1, md)).tocsr()  # noqa: E731
    A = whole("Grad_Test_u.Grad_Test2_u")[iu:iu + nu, iu:iu + nu]
    B = whole("Test_v*Test2_u")[iv:iv + nv, iu:iu + nu]
    C = whole("Test_v*Test2_v")[iv:iv + nv, iv:iv + nv]
    L = np.array(gf.asm("generic", mim, 1, "-0.6*Test_u", -1, md))[iu:iu + nu]
    return mfw, mfh, A.tocsc(), B.tocsc(), C.tocsc(), L


def initial_state(mfw, n):
    """u(0) interpolated at the vertices and, for P1+, at the centroids: the vertex dofs
    take the vertex values (the bubble vanishes there); each bubble dof the coefficient
    that makes the function exact at its cell's centroid."""
    nodes = mfw.basic_dof_nodes().T
    on_grid = np.all(np.abs(nodes * n - np.round(nodes * n)) < 1e-9, axis=1)
    U = np.zeros(len(nodes))
    U[on_grid] = [u0(p) for p in nodes[on_grid]]
    bubbles = np.flatnonzero(~on_grid)
    if len(bubbles):
        at = nodes[bubbles].T
        f0 = gf.compute(mfw, U, "interpolate on", at)
        unit = np.zeros(len(nodes))
        unit[bubbles] = 1.0
        fb = gf.compute(mfw, unit, "interpolate on", at)
        target = np.array([u0(p) for p in nodes[bubbles]])
        U[bubbles] = (target - np.asarray(f0).ravel()) / np.asarray(fb).ravel()
    return U, on_grid


def pdas(S, r, lower, active, factors):
    """min ½XᵀSX − rᵀX over X ≥ lower (lower = −∞ where unconstrained) by the primal-dual
    active set method; returns X and the active set, checked against the KKT conditions.
    `factors` keeps the LU of the last inactive block (steps often share an active set)."""
    bounded = np.isfinite(lower)
    for _ in range(100):
        inactive = np.flatnonzero(~active)
        X = np.where(active, lower, 0.0)
        rhs = r[inactive] - S[inactive][:, np.flatnonzero(active)] @ X[active]
        if factors.get("active") is None or not np.array_equal(factors["active"], active):
            factors["active"], factors["lu"] = active.copy(), splu(S[inactive][:, inactive].tocsc())
        X[inactive] = factors["lu"].solve(rhs)
        lam = S @ X - r
        new = bounded & (lam - 1e3 * (X - np.where(bounded, lower, 0.0)) > 0.0)
        if np.array_equal(new, active):
            break
        active = new
    else:
        raise SystemExit("pdas: no convergence in 100 iterations")
    scale = max(np.max(np.abs(X)), 1e-300)
    lam_scale = max(np.max(np.abs(r)), 1e-300)
    if (np.any(X[bounded] < lower[bounded] - 1e-12 * scale) or np.any(lam[active] < -1e-12 * lam_scale)
            or np.max(np.abs(lam[~active]), initial=0.0) > 1e-10 * lam_scale):
        raise SystemExit("pdas: KKT conditions fail at the returned point")
    return X, active


def main():
    p = argparse.ArgumentParser()
    p.add_argument("-pair", default="P1+/P0", choices=sorted(PAIRS))
    p.add_argument("-scheme", default="midpoint", choices=["backward_euler", "midpoint"])
    p.add_argument("-n", type=int, default=8)
    p.add_argument("-dt", type=float, default=0.002)
    p.add_argument("-steps", type=int, default=400)
    p.add_argument("-out", default="getfem_membrane_3d.csv")
    a = p.parse_args()
    mesh = cube_mesh(a.n)
    mfw, mfh, A, B, C, L = assemble(mesh, a.pair)
    U, vertex = initial_state(mfw, a.n)
    fixed_w = np.zeros(len(U), dtype=bool)
    fixed_w[mfw.basic_dof_on_region(1)] = True
    if a.pair == "P1/P1":  # a continuous velocity vanishes where u is fixed
        keep = np.setdiff1d(np.arange(mfh.nbdof()), mfh.basic_dof_on_region(1))
        B, C = B[keep, :], C[keep, :][:, keep]
    free = np.flatnonzero(~fixed_w)
    if C.nnz == C.shape[0]:  # P0: C is diagonal
        Cinv_B = (sp.diags(1.0 / C.diagonal()) @ B).tocsc()
    else:                    # P1: C⁻¹B, dense (the faces' columns fill in)
        Cinv_B = sp.csc_matrix(splu(C.tocsc()).solve(B.toarray()))
    M = (B.T @ Cinv_B).tocsc()

    nodes = mfw.basic_dof_nodes().T
    g = 0.01 - 0.04 * nodes[:, 2]
    lower = np.where(vertex[free], g[free], -np.inf)

    def at_point(point):
        return int(np.flatnonzero(np.all(np.abs(nodes - point) < 1e-12, axis=1))[0])
    centre, low = at_point([0.5, 0.5, 0.5]), at_point([0.5, 0.5, 0.125])

    midpoint = a.scheme == "midpoint"
    c = 1.0 / a.dt
    k, kv = (4 * c * c, 2 * c) if midpoint else (c * c, c)
    S = (k * M + A).tocsc()
    S_ff = S[free][:, free].tocsr()
    S_fb = S[free][:, np.flatnonzero(fixed_w)]
    U_b = U[fixed_w]
    V = np.zeros(B.shape[0])
    active = np.zeros(len(free), dtype=bool)
    factors = {}

    def row(step):
        kin = 0.5 * V @ (C @ V)
        pot = 0.5 * U @ (A @ U) - L @ U
        return (f"{step},{step * a.dt:.17g},{kin:.17g},{pot:.17g},{kin + pot:.17g},"
                f"{U[centre]:.17g},{U[low]:.17g},{int(np.count_nonzero(active))}\n")

    with open(a.out, "w") as f:
        f.write("step,t,E_kin,E_pot,E_total,u_centre,u_low,active\n")
        f.write(row(0))
        for step in range(1, a.steps + 1):
            r = k * (M @ U) + kv * (B.T @ V) + L
            X_f, active = pdas(S_ff, r[free] - S_fb @ U_b, lower, active, factors)
            X = U.copy()
            X[free] = X_f
            U_new = 2 * X - U if midpoint else X
            dV = Cinv_B @ (U_new - U)
            V = 2 * c * dV - V if midpoint else c * dV
            U = U_new
            f.write(row(step))


if __name__ == "__main__":
    main()
