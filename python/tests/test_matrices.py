"""The matrices A, B, C, L, M and G as seen from Python against the kernel's values.

Three kinds of check: (1) invariants of A and M = BᵀC⁻¹B computed here with scipy from
the exported arrays, against FreeFEM's numbers (data/reference/matrices_n*.csv, the
reference of tests/unit/test_reference_matrices.cpp, same tolerances); (2) the exported
arrays against the kernel's own operators on them (momentum, velocity, kinetic and
potential energy, max_violation), computed in C++; (3) the identities the C++ unit
tests assert (1ᵀM1 = ρ|Ω|, C of P0 = the cell measures, B 1 = ∫ψ_i, condition (12)'s
closed form for P1+/P0).  And that the arrays are views, not copies.
"""

import csv
import os

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse

import cdyn
from conftest import SOURCE_DIR


def dense_mass(mass):
    """M = Bᵀ C⁻¹ B from the exported arrays (M itself where the kernel has it)."""
    if mass.M is not None:
        return mass.M.toarray()
    B, C = mass.B.toarray(), mass.C.toarray()
    return B.T @ np.linalg.solve(C, B)


def membrane(n, pair, dirichlet=True, rho=1.0, obstacle=False):
    return cdyn.scalar_wave(cdyn.unit_square_mesh(n), mass=pair, rho=rho, f=0.0,
                            dirichlet_parts="all" if dirichlet else [], obstacle=obstacle)


def freefem(n):
    with open(os.path.join(SOURCE_DIR, "data", "reference", f"matrices_n{n}.csv")) as f:
        return {r["pair"]: r for r in csv.DictReader(f)}


@pytest.mark.parametrize("n", [4, 10])
@pytest.mark.parametrize("pair, ff_name", [("P1/P1", "P1/P1"), ("P1+/P0", "P1b/P0"), ("P2/P1", "P2/P1")])
def test_A_and_M_against_freefem(n, pair, ff_name):
    # The invariants of test_reference_matrices.cpp, whose tolerances (1e-12 on 1ᵀM1,
    # 1e-10 on the traces: dense solves with cond(A) ≈ 1e3) are justified there.
    ref = freefem(n)[ff_name]
    free = membrane(n, pair, dirichlet=False)
    one = free.W.interpolate(1.0)
    mass = one @ dense_mass(free.mass) @ one
    assert mass == pytest.approx(float(ref["mass"]), rel=1e-12)
    p = membrane(n, pair)
    Y = np.linalg.solve(p.A.toarray(), dense_mass(p.mass))
    assert np.trace(Y) == pytest.approx(float(ref["trace1"]), rel=1e-10)
    assert np.trace(Y @ Y) == pytest.approx(float(ref["trace2"]), rel=1e-10)


@pytest.mark.parametrize("pair", ["P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1", "consistent", "lumped"])
def test_mass_arrays_against_the_kernels_operators(pair):
    # M e_j from the exported arrays against the kernel's momentum(velocity(e_j)), and
    # ½VᵀCV against kinetic_energy.  Measured at n = 6: 3.7e-16 and 3.1e-16 relative at
    # most over the pairs (one rounding per entry); 1e-14 leaves a factor 30.
    p = membrane(6, pair)
    M = dense_mass(p.mass)
    n = p.n_free
    M_kernel = np.column_stack([p.mass.momentum(p.mass.velocity(np.eye(n)[:, j])) for j in range(n)])
    assert np.abs(M - M_kernel).max() <= 1e-14 * np.abs(M).max()
    V = np.random.default_rng(1).standard_normal(p.mass.n_velocity)
    C = p.mass.C
    assert 0.5 * V @ (C @ V) == pytest.approx(p.mass.kinetic_energy(V), rel=1e-14)


@pytest.mark.parametrize("pair", ["P1+/P0", "P2/P1", "consistent"])
def test_total_mass_is_rho_times_area(pair):
    # 1ᵀM1 = ρ|Ω| (the P1 part of 1_W; no Dirichlet condition), as the C++ tests assert.
    rho = 2.5
    p = membrane(5, pair, dirichlet=False, rho=rho)
    one = p.W.interpolate(1.0)
    assert one @ dense_mass(p.mass) @ one == pytest.approx(rho * 1.0, rel=1e-13)  # measured ≤ 7e-16


def test_A_is_the_restricted_laplacian_and_gives_the_potential_energy():
    mesh = cdyn.unit_square_mesh(6)
    p = cdyn.scalar_wave(mesh, f="-0.6", dirichlet_parts="all", dirichlet_value=0.02)
    A_full = cdyn.assemble_laplace(p.W)
    assert (p.A != p.bc.restrict_matrix(A_full)).nnz == 0          # the same arithmetic, bit for bit
    assert (p.A_full != A_full).nnz == 0
    assert np.abs(A_full @ p.W.interpolate(1.0)).max() <= 1e-13        # ∫∇φ_i·∇1 = 0 (measured 9e-16)
    U = np.random.default_rng(2).standard_normal(p.n_free)
    u = p.full(U)
    L = p.full_load(0.0)
    J = 0.5 * u @ (p.A_full @ u) - L @ u
    assert J == pytest.approx(p.potential_energy(U, 0.0), rel=1e-13)  # measured 0 (same sums)


def test_B_C_and_L_of_P1_bubble_over_P0():
    mesh = cdyn.unit_square_mesh(5)
    W, H = cdyn.FESpace(mesh, "P1+"), cdyn.FESpace(mesh, "P0")
    B, C = cdyn.assemble_mass(H, W), cdyn.assemble_mass(H, H)
    assert C.nnz == mesh.n_cells                                        # diagonal
    measures = np.array([mesh.cell_measure(c) for c in range(mesh.n_cells)])
    assert np.abs(C.diagonal() - measures).max() <= 1e-16
    one_H = cdyn.assemble_load(H, 1.0)                                  # ∫ψ_i
    assert np.abs(B @ W.interpolate(1.0) - one_H).max() <= 1e-14
    assert cdyn.assemble_load(cdyn.FESpace(mesh, "P1"), -0.6).sum() == pytest.approx(-0.6, rel=1e-13)
    # each bubble sits in the row of its cell only, with ∫_T 27λ0λ1λ2 = (9/20)|T|
    bubbles = B[:, mesh.n_vertices:].toarray()
    assert np.allclose(bubbles, np.diag(0.45 * measures), rtol=1e-14, atol=0)


def test_M_is_singular_and_Ker_B_carries_the_constraints():
    # P1+/P0: N_W = vertices + cells, rank B = N_H = cells, dim Ker B = free vertices;
    # β = σ_min(G Z) from numpy (Z = an orthonormal basis of Ker B) against the kernel's
    # condition12 on the same arrays and the closed form of test_wellposedness.cpp.
    n = 6
    p = membrane(n, "P1+/P0", obstacle=True)
    B = p.mass.B.toarray()
    G, alpha = p.G()
    assert np.linalg.matrix_rank(B) == p.mass.n_velocity == 2 * n * n
    Z = scipy.linalg.null_space(B)
    assert Z.shape[1] == (n - 1) ** 2 == G.shape[0]
    M = dense_mass(p.mass)
    assert np.abs(M @ Z).max() <= 1e-15                                 # massless directions
    beta_numpy = np.linalg.svd(G @ Z, compute_uv=False).min()
    w = cdyn.condition12(p.mass.B, G)
    assert w.satisfied and w.dim_ker_B == Z.shape[1]
    assert w.beta == pytest.approx(beta_numpy, rel=1e-12)               # measured 5e-16
    # the closed form: β = 1/sqrt(1 + (20/27)² λ_max(EᵀE)), E the cell–free vertex incidence
    mesh = p.W.mesh
    E = np.zeros((mesh.n_cells, p.n_free))
    for c, cell in enumerate(mesh.cells):
        for v in cell:
            if (f := p.bc.free_index(int(v))) >= 0:
                E[c, f] = 1.0
    lmax = np.linalg.eigvalsh(E.T @ E).max()
    assert w.beta == pytest.approx(1.0 / np.sqrt(1.0 + (20.0 / 27.0) ** 2 * lmax), abs=1e-13)


def test_G_and_alpha_describe_the_bounds():
    p = cdyn.scalar_wave(cdyn.unit_square_mesh(5), f=-0.6, dirichlet_parts="all", dirichlet_value=0.02, g="0.01*x")
    G, alpha = p.G()
    assert G.shape == (len(p.constrained), p.n_free)
    # one row −e_i per constrained (lower-bounded) unknown i
    assert np.array_equal(-G.T @ np.ones(G.shape[0]), np.isin(np.arange(p.n_free), p.constrained).astype(float))
    assert np.array_equal(alpha, -p.lower[p.constrained])
    for seed in range(3):
        U = np.random.default_rng(seed).uniform(-0.05, 0.05, p.n_free)
        assert max((G @ U - alpha).max(), 0.0) == p.max_violation(U, 0.0)


def test_views_are_not_copies():
    p = membrane(4, "P1+/P0")
    A1, A2 = p.A, p.A
    assert np.shares_memory(A1.data, A2.data) and np.shares_memory(A1.indices, A2.indices)
    assert not A1.data.flags.writeable                                  # the problem's own A
    with pytest.raises(ValueError):
        A1.data[0] = 1.0
    assert np.shares_memory(p.lower, p.lower) and not p.lower.flags.writeable
    mesh = p.W.mesh
    assert np.shares_memory(mesh.vertices, mesh.vertices) and mesh.vertices.shape == (25, 3)
    # an assembled matrix: scipy keeps the kernel's arrays (its data owns no memory of its own)
    A = cdyn.assemble_laplace(p.W)
    assert isinstance(A, scipy.sparse.csc_matrix) and not A.data.flags.owndata and A.data.flags.writeable
    assert A.indices.dtype == np.int32 and A.has_sorted_indices
