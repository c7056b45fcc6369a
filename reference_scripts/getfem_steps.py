"""getfem_steps.py — what the 3D step-by-step references share (getfem_membrane_3d.py,
getfem_cube_3d.py): GetFEM's sparse matrices in scipy, cdyn's nodal interpolant of an
initial field, and each step's bound-constrained QP solved by an active set loop that
checks its own KKT conditions.
"""
import getfem as gf
import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu


def scipy_matrix(M):
    """A GetFEM Spmat as a scipy CSC matrix."""
    jc, ir = M.csc_ind()
    n_rows, n_cols = M.size()
    return sp.csc_matrix((M.csc_val(), ir, jc), shape=(n_rows, n_cols))


def interpolant(mf, n, u):
    """cdyn's interpolant of u (a function of a point returning q values, q = mf.qdim())
    on the unit cube's grid of step 1/n: the vertex dofs take the vertex values (a bubble
    vanishes there), each bubble dof the coefficient that makes the function exact at its
    cell's centroid, whatever GetFEM's basis.  Returns the coefficients and the mask of
    the vertex dofs (GetFEM interleaves the q components of a node)."""
    q = mf.qdim()
    nodes = mf.basic_dof_nodes().T
    component = np.arange(len(nodes)) % q
    vertex = np.all(np.abs(nodes * n - np.round(nodes * n)) < 1e-9, axis=1)
    U = np.zeros(len(nodes))
    U[vertex] = [u(p)[k] for p, k in zip(nodes[vertex], component[vertex])]
    first = np.flatnonzero(~vertex & (component == 0))  # one bubble node, its q dofs from here
    if len(first):
        at = nodes[first].T
        unit = np.where(vertex, 0.0, 1.0)
        f0 = np.asarray(gf.compute(mf, U, "interpolate on", at)).reshape(q, -1)
        fb = np.asarray(gf.compute(mf, unit, "interpolate on", at)).reshape(q, -1)
        target = np.array([u(p) for p in nodes[first]]).T.reshape(q, -1)
        for k in range(q):
            U[first + k] = (target[k] - f0[k]) / fb[k]
    return U, vertex


def pdas(S, r, lower, active, factors):
    """min ½XᵀSX − rᵀX over X ≥ lower (lower = −∞ where unconstrained) by the primal-dual
    active set method; returns X and the active set, checked against the KKT conditions.
    `factors` keeps the LU of the last inactive block (steps often share an active set)."""
    bounded = np.isfinite(lower)
    bound = np.where(bounded, lower, 0.0)
    for _ in range(100):
        inactive = np.flatnonzero(~active)
        X = np.where(active, bound, 0.0)
        rhs = r[inactive] - S[inactive][:, np.flatnonzero(active)] @ X[active]
        if factors.get("active") is None or not np.array_equal(factors["active"], active):
            factors["active"], factors["lu"] = active.copy(), splu(S[inactive][:, inactive].tocsc())
        X[inactive] = factors["lu"].solve(rhs)
        lam = S @ X - r
        new = bounded & (lam - 1e3 * (X - bound) > 0.0)
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
