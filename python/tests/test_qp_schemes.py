"""The step QP and the schemes from Python: the midpoint step's QP written with the
exported matrices and solved by every step solver of the build, against the scheme's own
step; the energy identities stepped one step at a time.
"""

import numpy as np
import pytest

import cdyn


def membrane(n=8, obstacle=True):
    return cdyn.scalar_wave(cdyn.unit_square_mesh(n), f=-0.6, dirichlet_parts="all", dirichlet_value=0.02,
                            obstacle=obstacle)


def start(p):
    return cdyn.State(p.bc.restrict(p.W.interpolate(0.02)), np.zeros(p.mass.n_velocity))


@pytest.mark.parametrize("solver", cdyn.step_solver_names())
def test_the_midpoint_qp_by_hand_is_the_schemes_step(solver):
    # Midpoint with the constraint on the half step (docs/schemes.md): X = U^{n+½} solves
    # min ½XᵀSX − rᵀX over the bounds, S = 4M/dt² + A, r = 4MUⁿ/dt² + 2BᵀVⁿ/dt + L, and
    # U^{n+1} = 2X − Uⁿ (without the reconstruction of eq. 14).  From a state in contact
    # (after 260 steps) so that bounds are active.
    dt = 1e-3
    p = membrane()
    scheme = cdyn.time_scheme("midpoint", p, cdyn.step_solver("pdas", cdyn.QPOptions(tol=1e-12)), dt,
                              cdyn.SchemeParameters(reconstruct=False, tol=1e-12))
    s = start(p)
    for _ in range(260):
        scheme.step(s)
    M, B, A, L = p.mass.M, p.mass.B, p.A, p.load(s.t)
    qp = cdyn.BoundQP(S=4 * M / dt**2 + A, r=4 * M @ s.U / dt**2 + 2 * B.T @ s.V / dt + L, lower=p.lower)
    result = cdyn.step_solver(solver, cdyn.QPOptions(tol=1e-12)).solve(qp)
    assert result.converged and cdyn.kkt_residual(qp, result.X) <= 1e-12
    assert len(result.active) > 0
    U_before = s.U
    scheme.step(s)
    # The scheme solves the same QP with the bubbles condensed out; both to tol 1e-12 on
    # the KKT residual, which bounds the error in X only up to S's conditioning (4M/dt²
    # against A).  Measured max |ΔU|: pdas 5.1e-12, pgs 3.1e-11, ipopt 9.9e-15, nlopt 3.3e-14
    # (|U| ≈ 0.02).
    assert np.abs((2 * result.X - U_before) - s.U).max() <= 1e-10


def test_state_reads_are_snapshots():
    p = membrane(4)
    scheme = cdyn.time_scheme("backward_euler", p, cdyn.step_solver("pdas"), 1e-2)
    s = start(p)
    U0 = s.U
    scheme.step(s)
    assert s.t == pytest.approx(1e-2) and not np.array_equal(U0, s.U)
    assert np.array_equal(U0, p.bc.restrict(p.W.interpolate(0.02)))


def test_midpoint_without_contact_keeps_J_to_round_off():
    # Accumulated round-off (each step's QP solved to its tol, the full steps reconstructed):
    # measured 9.8e-13 relative over 80 steps at dt = 0.001 (n = 8, no obstacle).
    p = membrane(obstacle=False)
    scheme = cdyn.time_scheme("midpoint", p, cdyn.step_solver("pdas"), 1e-3)
    s = start(p)
    scheme.initialize(s)
    J0 = scheme.energy(s).total
    drift = 0.0
    for _ in range(80):
        scheme.step(s)
        drift = max(drift, abs(scheme.energy(s).total - J0) / abs(J0))
    assert drift <= 1e-11


def test_backward_euler_never_increases_J():
    p = membrane()
    scheme = cdyn.time_scheme("backward_euler", p, cdyn.step_solver("pdas"), 2e-3)
    s = start(p)
    J = scheme.energy(s).total
    active = 0
    for _ in range(400):
        active = max(active, scheme.step(s).active)
        J_next = scheme.energy(s).total
        assert J_next < J   # measured: J falls by at least 5e-5 J per step (dt = 0.002)
        J = J_next
    assert active > 0  # the impact happened


def test_scheme_parameters_reach_the_scheme():
    p = cdyn.oscillator(cdyn.oscillator_mesh(), m=1.0, k=1.0)
    s = cdyn.State(np.array([1.0]), np.zeros(1))
    scheme = cdyn.time_scheme("paoli_schatzman", p, cdyn.step_solver("pdas"), 0.01,
                              cdyn.SchemeParameters(restitution=0.5))
    J0 = scheme.energy(s).total
    for _ in range(314):  # past the first impact at t = π/2, before the second
        scheme.step(s)
    # restitution e = 0.5 keeps e² = 1/4 of J (docs/experiments.md); measured 0.2499938
    assert scheme.energy(s).total / J0 == pytest.approx(0.25, abs=1e-4)


def test_damping_reaches_the_scheme():
    # The oscillator without obstacle, m = k = 1, α = 0.2: J + W_d = J0 step by step
    # (midpoint: round-off, measured at most 2.0e-12 J0 over the 400 steps), and J(2π)
    # that of the damped solution u = e^{−at}(cos ω_d t + (a/ω_d) sin ω_d t), a = ζω = α/2,
    # ω_d = (1 − a²)^½, to the scheme's O(dt²) (measured 5.2e-5 relative).
    p = cdyn.oscillator(cdyn.oscillator_mesh(), m=1.0, k=1.0, obstacle=False)
    s = cdyn.State(np.array([1.0]), np.zeros(1))
    scheme = cdyn.time_scheme("midpoint", p, cdyn.step_solver("pdas"), 2 * np.pi / 400,
                              cdyn.SchemeParameters(damping_alpha=0.2))
    J0, W = scheme.energy(s).total, 0.0
    for _ in range(400):
        W += scheme.step(s).dissipated
        assert abs(scheme.energy(s).total + W - J0) <= 1e-11 * J0
    a, t = 0.1, 2 * np.pi
    wd = np.sqrt(1 - a * a)
    u = np.exp(-a * t) * (np.cos(wd * t) + a / wd * np.sin(wd * t))
    v = -np.exp(-a * t) * (wd + a * a / wd) * np.sin(wd * t)
    assert scheme.energy(s).total == pytest.approx(0.5 * (u * u + v * v), rel=2e-4)
    with pytest.raises(cdyn.InputError, match="takes no damping"):
        cdyn.time_scheme("newmark", p, cdyn.step_solver("pdas"), 0.01, cdyn.SchemeParameters(damping_alpha=0.2))
