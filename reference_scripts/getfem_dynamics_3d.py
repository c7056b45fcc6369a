#!/usr/bin/python3
"""getfem_dynamics_3d.py — two of cdyn's 3D scenes integrated step by step with GetFEM's
tetrahedral elements and scipy: an independent reference for cdyn's 3D pairs, schemes and
contact (tests/reference, docs/three_d.md).

-model membrane (data/scenes/membrane_3d.toml): the scalar wave with an obstacle,
    u_tt − Δu = −0.6 in (0, 1)³, u = 0.02 on the six faces, u(a) ≥ 0.01 − 0.04 z at
    every vertex a, u(0) = 0.02 + 0.02 sin(πx) sin(πy) sin(πz), u_t(0) = 0.
-model elasticity (data/scenes/cube_3d.toml): the free elastic cube falling on a plane,
    ρ u_tt − div σ(u) = 0, E = 1, ν = 0.3, ρ = 1 (σ = λ tr ε I + 2μ ε), u(0) = 0,
    u_t(0) = −0.1 e_z, the vertices of the face z = 0 kept above the plane z = −h/2:
    u_z(a) ≥ −h/2 (the plane's normal is e_z: no rotation of the contact nodes).

Mesh: cdyn's unit_cube (n³ cells of six tetrahedra, getfem_matrices.cube_mesh).  Pairs
(seed eqs. 10–11), with q = 1 or 3 components: P1/P1 (FEM_PK(3,1) twice; velocity dofs
where u is fixed dropped, as cdyn drops those of a Dirichlet boundary) and P1+/P0
(FEM_PK_WITH_CUBIC_BUBBLE(3,1), P1 plus the quartic bubble, and
FEM_PK_DISCONTINUOUS(3,0)); B_ij = ∫ψ_i·φ_j, C_ij = ∫ψ_i·ψ_j, A from ∫∇φ_i·∇φ_j or
∫σ(φ_j):ε(φ_i), L_i = ∫f φ_i, with IM_TETRAHEDRON(8) (exact for every product here),
M = Bᵀ C⁻¹ B.  U⁰ and U̇⁰ interpolate the initial fields as cdyn does
(getfem_steps.interpolant), and C V⁰ = B U̇⁰ (seed eq. 11).

Schemes (docs/schemes.md), c = 1/dt:
  backward_euler: X = U^{n+1}, S = c² M + A, r = c² M Uⁿ + c Bᵀ Vⁿ + L,
                  V^{n+1} = c C⁻¹B (U^{n+1} − Uⁿ);
  midpoint:       X = U^{n+½}, S = 4c² M + A, r = 4c² M Uⁿ + 2c Bᵀ Vⁿ + L,
                  U^{n+1} = 2X − Uⁿ, V^{n+1} = 2c C⁻¹B (U^{n+1} − Uⁿ) − Vⁿ
                  (the full step extrapolated: cdyn with time.reconstruct = false).
Each step minimizes ½XᵀSX − rᵀX over the dofs not fixed, with the bounds, by the
active set loop of getfem_steps.pdas (it stops the script if a step's KKT conditions
fail).

    /usr/bin/python3 reference_scripts/getfem_dynamics_3d.py -model membrane -pair P1+/P0 -scheme midpoint -n 8 -dt 0.002 -steps 400 -out m3.csv
writes  step,t,E_kin,E_pot,E_total,active and the probes of cdyn's history.csv, under
cdyn's names (membrane: u@centre, u@low at (½, ½, ½), (½, ½, ⅛); elasticity: ux, uy, uz
at bottom (½, ½, 0) and top (½, ½, 1)); E_kin = ½VᵀCV, E_pot = ½UᵀAU − LᵀU on the
whole field, active = the bounds held at the step's solution.
"""
import argparse
import math

import getfem as gf
import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from getfem_matrices import cube_mesh
from getfem_steps import interpolant, pdas, scipy_matrix

PAIRS = {"P1/P1": ("FEM_PK(3,1)", "FEM_PK(3,1)"),
         "P1+/P0": ("FEM_PK_WITH_CUBIC_BUBBLE(3,1)", "FEM_PK_DISCONTINUOUS(3,0)")}


def bump(p):
    return math.sin(math.pi * p[0]) * math.sin(math.pi * p[1]) * math.sin(math.pi * p[2])


# Each model: components, A's integrand, the load, u(0), u_t(0), probes {name: point}.
E, NU = 1.0, 0.3
LAME_LAMBDA, LAME_MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
MODELS = {
    "membrane": dict(q=1, stiffness="Grad_Test_u.Grad_Test2_u", load="-0.6*Test_u",
                     u0=lambda p: [0.02 + 0.02 * bump(p)], v0=lambda p: [0.0],
                     probes={"centre": [0.5, 0.5, 0.5], "low": [0.5, 0.5, 0.125]}),
    "elasticity": dict(q=3, stiffness=f"{LAME_LAMBDA!r}*Div_Test_u*Div_Test2_u"
                                      f" + 2*{LAME_MU!r}*(Sym(Grad_Test_u):Sym(Grad_Test2_u))",
                       load=None, u0=lambda p: [0.0, 0.0, 0.0], v0=lambda p: [0.0, 0.0, -0.1],
                       probes={"bottom": [0.5, 0.5, 0.0], "top": [0.5, 0.5, 1.0]}),
}


def assemble(mesh, pair, model):
    q = model["q"]
    mim = gf.MeshIm(mesh, gf.Integ("IM_TETRAHEDRON(8)"))
    mfw, mfh = gf.MeshFem(mesh, q), gf.MeshFem(mesh, q)
    mfw.set_fem(gf.Fem(PAIRS[pair][0]))
    mfh.set_fem(gf.Fem(PAIRS[pair][1]))
    md = gf.Model("real")
    md.add_fem_variable("u", mfw)
    md.add_fem_variable("v", mfh)
    iu, nu = md.interval_of_variable("u")
    iv, nv = md.interval_of_variable("v")
    whole = lambda expr: scipy_matrix(gf.asm("generic", mim, 2, expr, -1, md)).tocsr()  # noqa: E731
    A = whole(model["stiffness"])[iu:iu + nu, iu:iu + nu]
    B = whole("Test_v.Test2_u")[iv:iv + nv, iu:iu + nu]
    C = whole("Test_v.Test2_v")[iv:iv + nv, iv:iv + nv]
    L = np.zeros(nu) if model["load"] is None else np.array(gf.asm("generic", mim, 1, model["load"], -1, md))[iu:iu + nu]
    return mfw, mfh, A.tocsc(), B.tocsc(), C.tocsc(), L


def main():
    p = argparse.ArgumentParser()
    p.add_argument("-model", default="membrane", choices=sorted(MODELS))
    p.add_argument("-pair", default="P1+/P0", choices=sorted(PAIRS))
    p.add_argument("-scheme", default="midpoint", choices=["backward_euler", "midpoint"])
    p.add_argument("-n", type=int, default=8)
    p.add_argument("-dt", type=float, default=0.002)
    p.add_argument("-steps", type=int, default=400)
    p.add_argument("-out", default="getfem_dynamics_3d.csv")
    a = p.parse_args()
    model = MODELS[a.model]
    q = model["q"]
    mesh = cube_mesh(a.n)
    mfw, mfh, A, B, C, L = assemble(mesh, a.pair, model)
    U, vertex = interpolant(mfw, a.n, model["u0"])
    U_rate, _ = interpolant(mfw, a.n, model["v0"])
    nodes = mfw.basic_dof_nodes().T
    component = np.arange(len(U)) % q
    fixed_w = np.zeros(len(U), dtype=bool)
    if a.model == "membrane":  # u = 0.02 on the faces; u ≥ g at every free vertex
        fixed_w[mfw.basic_dof_on_region(1)] = True
        bound = np.where(vertex, 0.01 - 0.04 * nodes[:, 2], -np.inf)
    else:                      # u_z ≥ −h/2 at the vertices of the face z = 0
        bound = np.where(vertex & (component == 2) & (np.abs(nodes[:, 2]) < 1e-12), -0.5 / a.n, -np.inf)
    if a.pair == "P1/P1" and fixed_w.any():  # a continuous velocity vanishes where u is fixed
        keep = np.setdiff1d(np.arange(mfh.nbdof()), mfh.basic_dof_on_region(1))
        B, C = B[keep, :], C[keep, :][:, keep]
    free = np.flatnonzero(~fixed_w)
    if C.nnz == C.shape[0]:  # P0: C is diagonal
        Cinv_B = (sp.diags(1.0 / C.diagonal()) @ B).tocsc()
    else:                    # P1: C⁻¹B, dense (the faces' columns fill in)
        Cinv_B = sp.csc_matrix(splu(C.tocsc()).solve(B.toarray()))
    M = (B.T @ Cinv_B).tocsc()
    V = Cinv_B @ U_rate
    lower = bound[free]

    def dof_at(point, k):
        return int(np.flatnonzero(np.all(np.abs(nodes - point) < 1e-12, axis=1) & (component == k))[0])
    names = ["u"] if q == 1 else ["ux", "uy", "uz"]
    probes = [(f"{names[k]}@{name}", dof_at(x, k)) for name, x in model["probes"].items() for k in range(q)]

    midpoint = a.scheme == "midpoint"
    c = 1.0 / a.dt
    k, kv = (4 * c * c, 2 * c) if midpoint else (c * c, c)
    S = (k * M + A).tocsc()
    S_ff = S[free][:, free].tocsr()
    S_fb = S[free][:, np.flatnonzero(fixed_w)]
    U_b = U[fixed_w]
    active = np.zeros(len(free), dtype=bool)
    factors = {}

    def row(step):
        kin = 0.5 * V @ (C @ V)
        pot = 0.5 * U @ (A @ U) - L @ U
        values = ",".join(f"{U[i]:.17g}" for _, i in probes)
        return f"{step},{step * a.dt:.17g},{kin:.17g},{pot:.17g},{kin + pot:.17g},{np.count_nonzero(active)},{values}\n"

    with open(a.out, "w") as f:
        f.write("step,t,E_kin,E_pot,E_total,active," + ",".join(name for name, _ in probes) + "\n")
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
