"""cdyn: a reference kernel for dynamic contact (Renard's well-posed semi-discretizations).

Two levels (docs/python.md):

runs, the command line's code:
    cdyn.run(scene=None, set=None, out=None)      history, summary, fields of `cdyn run`
    cdyn.study(scene, vary={...})                 study.csv of `cdyn study`
    cdyn.wellposed(scene)                         condition (12) for every pair
    cdyn.simulation(scene)                        the mesh, problem, scheme a run integrates

the kernel, stage by stage (docs/kernel_map.md):
    meshes      unit_square_mesh, interval_mesh, read_mesh (gmsh), Mesh
    spaces      Element, FESpace, DirichletLift
    matrices    assemble_laplace (A), assemble_mass (B, C), assemble_load (L),
                make_mass_model / mixed_blocks (M = Bᵀ C⁻¹ B), ConstrainedProblem.G
    problems    scalar_wave, oscillator, ConstrainedProblem
    (12)        condition12, condition12_on, vertex_constraint_matrix
    step QP     BoundQP, step_solver(name), step_solver_names(), kkt_residual
    schemes     time_scheme(name, problem, solver, dt), State, step(), energy()

Matrices are scipy.sparse CSC matrices, viewing the kernel's own arrays where it keeps
them.  Errors: cdyn.InputError (a ValueError) and cdyn.NumericalError (a RuntimeError),
with the command line's messages.
"""

from ._cdyn import *  # noqa: F401,F403  (the kernel's classes and functions)
from ._cdyn import InputError, NumericalError, Simulation, __version__, default_scene  # noqa: F401
from .runs import run, scene_text, simulation, study, wellposed  # noqa: F401
