#!/usr/bin/python3
"""getfem_bar.py — the clamped bar impact (docs/bar_impact.md §3, data/scenes/bar.toml) integrated
with GetFEM's matrices and a step solved in closed form: an independent run to compare
with `cdyn run data/scenes/bar.toml --set method.mass=consistent` (docs/verification.md).

    ρ u_tt − E u_xx = 0 on (0, 1), E = ρ = 1, u(1) = 0, u(0, t) ≥ 0,
    u(x, 0) = (1 − x)/2, u_t(x, 0) = 0,

P1 (FEM_PK(1,1)) on n cells with the consistent mass M and the stiffness A assembled by
GetFEM (exact integration).  Each step of backward Euler or midpoint (constraint on the
half step; docs/schemes.md) minimizes ½XᵀSX − rᵀX over X_0 ≥ 0 — one bound, so the QP
is solved exactly: solve S X = r; if X_0 < 0, fix X_0 = 0 and solve for the others.
No code is shared with cdyn.

    /usr/bin/python3 reference_scripts/getfem_bar.py -n 40 -dt 0.0125 -steps 480 -scheme backward_euler -out bar.csv
writes  step,t,E_total,u_contact  (E = ½VᵀMV + ½UᵀAU, u_contact = u(0, t)).
"""
import argparse

import getfem as gf
import numpy as np


def assemble(n):
    m = gf.Mesh("cartesian", np.linspace(0.0, 1.0, n + 1))
    mf = gf.MeshFem(m, 1)
    mf.set_fem(gf.Fem("FEM_PK(1,1)"))
    mim = gf.MeshIm(m, gf.Integ("IM_GAUSS1D(4)"))
    md = gf.Model("real")
    md.add_fem_variable("u", mf)
    M = np.array(gf.asm("generic", mim, 2, "Test_u*Test2_u", -1, md).full())
    A = np.array(gf.asm("generic", mim, 2, "Grad_Test_u.Grad_Test2_u", -1, md).full())
    x = mf.basic_dof_nodes()[0]
    return M, A, x


def main():
    p = argparse.ArgumentParser()
    p.add_argument("-n", type=int, default=40)
    p.add_argument("-dt", type=float, default=0.0125)
    p.add_argument("-steps", type=int, default=480)
    p.add_argument("-scheme", default="backward_euler", choices=["backward_euler", "midpoint"])
    p.add_argument("-out", default="getfem_bar.csv")
    a = p.parse_args()
    M, A, x = assemble(a.n)
    free = [i for i in range(len(x)) if abs(x[i] - 1.0) > 1e-12]   # u(1) = 0: drop that dof
    contact = int(np.argmin(np.abs(x[free])))                       # the dof at x = 0
    M, A, x = M[np.ix_(free, free)], A[np.ix_(free, free)], x[free]
    c = 1.0 / a.dt
    k = 4.0 if a.scheme == "midpoint" else 1.0
    S = k * c * c * M + A
    U = (1.0 - x) / 2.0
    V = np.zeros_like(U)
    others = [i for i in range(len(x)) if i != contact]
    S_oo = S[np.ix_(others, others)]

    def step_qp(r):
        X = np.linalg.solve(S, r)
        if X[contact] < 0.0:                  # the bound is active: X_0 = 0
            X = np.zeros_like(r)
            X[others] = np.linalg.solve(S_oo, r[others])
        return X

    def energy():
        return 0.5 * V @ M @ V + 0.5 * U @ A @ U

    with open(a.out, "w") as f:
        f.write("step,t,E_total,u_contact\n")
        f.write(f"0,0,{energy():.17g},{U[contact]:.17g}\n")
        for n in range(1, a.steps + 1):
            if a.scheme == "backward_euler":
                X = step_qp(c * c * M @ U + c * M @ V)
                V = c * (X - U)
                U = X
            else:
                X = step_qp(4 * c * c * M @ U + 2 * c * M @ V)
                U1 = 2 * X - U
                V = 2 * c * (U1 - U) - V
                U = U1
            f.write(f"{n},{n * a.dt:.17g},{energy():.17g},{U[contact]:.17g}\n")


if __name__ == "__main__":
    main()
