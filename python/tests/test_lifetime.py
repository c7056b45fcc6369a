"""Lifetimes across the boundary: a view outliving the object whose storage it shows,
an object outliving the ones the kernel keeps references to (a space its mesh, a
problem its mesh, a scheme its problem and solver), must neither crash nor change.

Each test keeps only the inner object, drops every other reference, collects, churns
the allocator with objects of the same sizes (so that freed storage would be reused),
then checks the values against a copy taken from an independent twin.
"""

import gc

import numpy as np
import pytest

import cdyn


def churn():
    gc.collect()
    garbage = [cdyn.scalar_wave(cdyn.unit_square_mesh(6), f=1.0, dirichlet_parts="all") for _ in range(5)]
    del garbage
    gc.collect()


def problem(n=6):
    return cdyn.scalar_wave(cdyn.unit_square_mesh(n), f=-0.6, dirichlet_parts="all", dirichlet_value=0.02)


def test_matrix_outlives_its_problem_and_mesh():
    expected_A, expected_lower = problem().A.toarray(), problem().lower.copy()
    p = problem()
    A, lower, M = p.A, p.lower, p.mass.M
    expected_M = M.toarray()
    del p
    churn()
    assert np.array_equal(A.toarray(), expected_A)
    assert np.array_equal(lower, expected_lower)
    assert np.array_equal(M.toarray(), expected_M)


def test_space_and_views_outlive_their_mesh():
    expected = cdyn.FESpace(cdyn.unit_square_mesh(3), "P1+").dof_points.copy()
    W = cdyn.FESpace(cdyn.unit_square_mesh(3), "P1+")   # the mesh is only held by the space
    vertices = W.mesh.vertices
    churn()
    assert np.array_equal(W.dof_points, expected)
    assert np.array_equal(vertices, expected[:16])
    assert W.interpolate("x + y").shape == (16 + 18,)


def test_problem_and_mass_outlive_their_mesh():
    mass = problem().mass                                  # a part of a problem nobody holds
    churn()
    V = np.ones(mass.n_velocity)
    assert mass.kinetic_energy(V) == pytest.approx(0.5 * V @ (mass.C @ V), rel=1e-15)  # one rounding apart


def test_scheme_outlives_its_problem_and_solver():
    def midpoint():
        p = problem()
        return cdyn.time_scheme("midpoint", p, cdyn.step_solver("pdas"), 1e-3), p.full(p.bc.restrict(p.W.interpolate(0.02)))
    twin, _ = midpoint()
    scheme, _ = midpoint()                                 # problem and solver kept by the scheme alone
    churn()
    p = problem()
    states = [cdyn.State(p.bc.restrict(p.W.interpolate(0.02)), np.zeros(p.mass.n_velocity)) for _ in range(2)]
    for s, sch in zip(states, (scheme, twin)):
        sch.initialize(s)
        for _ in range(30):
            sch.step(s)
    assert np.array_equal(states[0].U, states[1].U)
    assert scheme.energy(states[0]).total == twin.energy(states[1]).total


def test_simulation_parts_outlive_the_simulation():
    twin = cdyn.simulation(set={"mesh.n": 4})
    expected_A = twin.problem.A.toarray()
    problem, mesh = cdyn.simulation(set={"mesh.n": 4}).problem, cdyn.simulation(set={"mesh.n": 4}).mesh
    churn()
    assert np.array_equal(problem.A.toarray(), expected_A)
    assert np.array_equal(mesh.vertices, twin.mesh.vertices)
