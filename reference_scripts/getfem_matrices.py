#!/usr/bin/python3
"""getfem_matrices.py — the invariants of reference_scripts/matrices.edp computed by GetFEM
(python3-getfem): a second independent program for cdyn's A and M = Bᵀ C⁻¹ B.

GetFEM has P1+ as FEM_PK_WITH_CUBIC_BUBBLE(2,1) (P1 plus the cubic bubble, its own
basis), P0 as FEM_PK_DISCONTINUOUS(2,0).  On FreeFEM's square(n,n) mesh (each cell split
along its lower-left to upper-right diagonal, built here triangle by triangle) it writes
the basis-independent numbers

    mass   = 1ᵀ M 1 (no Dirichlet condition; 1 the coefficients of the constant 1),
    trace1 = tr(A_ff⁻¹ M_ff),   trace2 = tr((A_ff⁻¹ M_ff)²)   (u = 0 on ∂Ω),

for P1/P1, P1+/P0 and P2/P1 (continuous velocities vanish on ∂Ω, as in cdyn), with the
exact integration IM_TRIANGLE(13) and dense linear algebra (numpy).

    /usr/bin/python3 reference_scripts/getfem_matrices.py -n 4 -out getfem_matrices_n4.csv
writes  pair,n,ndof,mass,trace1,trace2  (the CSV layout of matrices.edp; the pair named
P1b/P0 there is P1+/P0 here).

With -dim 3 the same on the unit cube cut into n³ cells of six tetrahedra (cdyn's
unit_cube_mesh: the Kuhn split around each cell's diagonal from (0,0,0) to (1,1,1)),
with GetFEM's 3D elements FEM_PK(3,1), FEM_PK_WITH_CUBIC_BUBBLE(3,1) (P1 plus the
quartic bubble of the tetrahedron: GetFEM's name is that of the 2D element),
FEM_PK_DISCONTINUOUS(3,0), FEM_PK(3,2), and IM_TETRAHEDRON(8), exact for the bubble's
mass (degree 8):
    /usr/bin/python3 reference_scripts/getfem_matrices.py -dim 3 -n 2 -out getfem_matrices_3d_n2.csv
"""
import argparse

import getfem as gf
import numpy as np


def square_mesh(n):
    m = gf.Mesh("empty", 2)
    gt = gf.GeoTrans("GT_PK(2,1)")
    for j in range(n):
        for i in range(n):
            x0, x1, y0, y1 = i / n, (i + 1) / n, j / n, (j + 1) / n
            m.add_convex(gt, np.array([[x0, x1, x1], [y0, y0, y1]]))
            m.add_convex(gt, np.array([[x0, x1, x0], [y0, y1, y1]]))
    m.set_region(1, m.outer_faces())
    return m


def cube_mesh(n):
    """The Kuhn cube of cdyn's unit_cube_mesh: in each cell, one tetrahedron per ordering
    (a, b, c) of the axes, from the cell's lowest corner along e_a, e_b, e_c."""
    m = gf.Mesh("empty", 3)
    gt = gf.GeoTrans("GT_PK(3,1)")
    orders = [(0, 1, 2), (1, 2, 0), (2, 0, 1), (0, 2, 1), (2, 1, 0), (1, 0, 2)]
    for k in range(n):
        for j in range(n):
            for i in range(n):
                for order in orders:
                    at = [i, j, k]
                    corners = [list(at)]
                    for axis in order:
                        at[axis] += 1
                        corners.append(list(at))
                    m.add_convex(gt, np.array(corners, dtype=float).T / n)
    m.set_region(1, m.outer_faces())
    return m


def fem(m, name):
    mf = gf.MeshFem(m, 1)
    mf.set_fem(gf.Fem(name))
    return mf


def matrices(mim, mfw, mfh):
    md = gf.Model("real")
    md.add_fem_variable("u", mfw)
    A = np.array(gf.asm("generic", mim, 2, "Grad_Test2_u.Grad_Test_u", -1, md).full())
    md2 = gf.Model("real")
    md2.add_fem_variable("v", mfh)
    md2.add_fem_variable("u", mfw)
    v0, nv = md2.interval_of_variable("v")
    u0, nu = md2.interval_of_variable("u")
    full = np.array(gf.asm("generic", mim, 2, "Test_v*Test2_u", -1, md2).full())
    B = full[v0:v0 + nv, u0:u0 + nu]       # B_ij = ∫ψ_i φ_j
    full = np.array(gf.asm("generic", mim, 2, "Test_v*Test2_v", -1, md2).full())
    C = full[v0:v0 + nv, v0:v0 + nv]       # C_ij = ∫ψ_i ψ_j
    return A, B, C


def invariants(m, mim, wname, hname):
    mfw, mfh = fem(m, wname), fem(m, hname)
    A, B, C = matrices(mim, mfw, mfh)
    # the coefficients of the constant 1: its L2 projection on W^h, exact since 1 ∈ W^h
    # (interpolation is not: GetFEM's bubble dof of this element is not a nodal value)
    md = gf.Model("real")
    md.add_fem_variable("u", mfw)
    MW = np.array(gf.asm("generic", mim, 2, "Test_u*Test2_u", -1, md).full())
    one_w = np.linalg.solve(MW, np.array(gf.asm("generic", mim, 1, "Test_u", -1, md)))
    M_all = B.T @ np.linalg.solve(C, B)
    mass = one_w @ M_all @ one_w
    fixed_w = set(mfw.basic_dof_on_region(1))
    free_w = [i for i in range(mfw.nbdof()) if i not in fixed_w]
    if hname.startswith("FEM_PK_DISCONTINUOUS("):
        free_h = list(range(mfh.nbdof()))
    else:                                  # a continuous velocity vanishes where u is fixed
        fixed_h = set(mfh.basic_dof_on_region(1))
        free_h = [i for i in range(mfh.nbdof()) if i not in fixed_h]
    Bf = B[np.ix_(free_h, free_w)]
    M = Bf.T @ np.linalg.solve(C[np.ix_(free_h, free_h)], Bf)
    Y = np.linalg.solve(A[np.ix_(free_w, free_w)], M)
    return mfw.nbdof(), mass, np.trace(Y), np.trace(Y @ Y)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("-n", type=int, default=4)
    p.add_argument("-dim", type=int, default=2, choices=[2, 3])
    p.add_argument("-out", default=None)
    a = p.parse_args()
    d = a.dim
    out = a.out or (f"getfem_matrices_n{a.n}.csv" if d == 2 else f"getfem_matrices_3d_n{a.n}.csv")
    m = square_mesh(a.n) if d == 2 else cube_mesh(a.n)
    mim = gf.MeshIm(m, gf.Integ("IM_TRIANGLE(13)" if d == 2 else "IM_TETRAHEDRON(8)"))
    rows = [("P1/P1", f"FEM_PK({d},1)", f"FEM_PK({d},1)"),
            ("P1b/P0", f"FEM_PK_WITH_CUBIC_BUBBLE({d},1)", f"FEM_PK_DISCONTINUOUS({d},0)"),
            ("P2/P1", f"FEM_PK({d},2)", f"FEM_PK({d},1)")]
    with open(out, "w") as f:
        f.write("pair,n,ndof,mass,trace1,trace2\n")
        for name, w, h in rows:
            ndof, mass, t1, t2 = invariants(m, mim, w, h)
            f.write(f"{name},{a.n},{ndof},{mass:.17g},{t1:.17g},{t2:.17g}\n")
            print(f"{name} n = {a.n}: 1'M1 = {mass:.15g}, tr(A^-1 M) = {t1:.15g}")


if __name__ == "__main__":
    main()
