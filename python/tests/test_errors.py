"""Errors from Python: cdyn.InputError (a ValueError) and cdyn.NumericalError (a
RuntimeError) carry the command line's one-line message, the text after "cdyn: error: "
or "cdyn: numerical failure: "; warnings arrive as RuntimeWarnings with the text after
"cdyn: warning: "."""

import os

import numpy as np
import pytest

import cdyn

# Bad input of tests/cli/CMakeLists.txt (cli_run_*): the arguments after `cdyn run`.
BAD_INPUT = [
    ["--set", "time.dt=-1"],
    ["--set", "time.tdt=1"],
    ["--set", "physics.f=sin(x"],
    ["no_such_scene.toml"],
    ["--set", "method.pair=Q1/P0"],
    ["--set", "time.scheme=leapfrog"],
    ["--set", "time.scheme=paoli_schatzman"],
    ["--set", "initial.u=-0.1"],
    ["--set", "mesh.kind=gmsh", "--set", "mesh.file=no_such_mesh.geo"],
]


def cli_message(stderr, prefix):
    lines = [l for l in stderr.splitlines() if l.startswith(prefix)]
    assert len(lines) == 1, stderr
    return lines[0][len(prefix):]


def test_the_exceptions_are_python_errors():
    assert issubclass(cdyn.InputError, ValueError) and issubclass(cdyn.NumericalError, RuntimeError)
    assert not issubclass(cdyn.InputError, RuntimeError)


@pytest.mark.parametrize("args", BAD_INPUT, ids=lambda a: " ".join(a))
def test_bad_input_has_the_command_lines_message(cli, args, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, _, err = cli("run", *args, "--out", "out_cli", cwd=tmp_path)
    assert status == 2
    scene = next((a for a in args if a.endswith(".toml")), None)
    sets = [a for i, a in enumerate(args) if i > 0 and args[i - 1] == "--set"]
    with pytest.raises(cdyn.InputError) as e:
        cdyn.run(scene, set=sets, out="out_py")
    assert str(e.value) == cli_message(err, "cdyn: error: ")
    assert not (tmp_path / "out_py" / "summary.json").exists()


def test_a_dict_of_overrides_gives_the_same_message(cli):
    _, _, err = cli("run", "--set", "time.dt=-1")
    with pytest.raises(cdyn.InputError, match="^time.dt: must be positive$") as e:
        cdyn.run(set={"time.dt": -1})
    assert str(e.value) == cli_message(err, "cdyn: error: ")
    with pytest.raises(cdyn.InputError, match="^dict: unknown key 'tiem'$"):
        cdyn.run({"tiem": {"dt": 0.1}})


def test_a_blow_up_has_the_command_lines_message(cli, scene, tmp_path, monkeypatch):
    # docs/outputs.md's example: Paoli–Schatzman above its stability limit.
    monkeypatch.chdir(tmp_path)
    sets = ["method.mass=lumped", "time.scheme=paoli_schatzman", "mesh.n=100"]
    status, _, err = cli("run", scene("bar"), *sum((["--set", s] for s in sets), []), "--out", "blowup", cwd=tmp_path)
    assert status == 3
    with pytest.raises(cdyn.NumericalError) as e, pytest.warns(RuntimeWarning) as w:
        cdyn.run(scene("bar"), set=sets, out="blowup")
    assert str(e.value) == cli_message(err, "cdyn: numerical failure: ")
    assert [str(x.message) for x in w] == [cli_message(err, "cdyn: warning: ")]  # dt above the stability limit
    assert str(e.value).startswith("step 263 (t = 3.2875)")


def test_warnings_have_the_command_lines_text(cli, tmp_path):
    sets = ["mesh.n=4", "time.T=0.0105", "output.fields=false", "output.plots=false"]
    _, _, err = cli("run", *sum((["--set", s] for s in sets), []), "--out", tmp_path / "cli")
    with pytest.warns(RuntimeWarning) as w:
        r = cdyn.run(set=sets, out=tmp_path / "py")
    assert [str(x.message) for x in w] == [cli_message(err, "cdyn: warning: ")]
    assert r["summary"]["warnings"] == [str(w[0].message)]


def test_study_errors_name_the_run(cli, tmp_path):
    _, _, err = cli("study", "--vary", "time.dt=0.01,-1", "--set", "mesh.n=4", "--out", tmp_path / "cli")
    with pytest.raises(cdyn.InputError) as e:
        cdyn.study(vary={"time.dt": [0.01, -1]}, set={"mesh.n": 4}, out=tmp_path / "py")
    assert str(e.value) == cli_message(err, "cdyn: error: ")
    assert str(e.value).startswith("run_001 (time.dt=-1): time.dt: must be positive")


def test_kernel_errors():
    mesh = cdyn.unit_square_mesh(2)
    with pytest.raises(cdyn.InputError, match="components"):
        cdyn.FESpace(mesh, "P1", 3)
    with pytest.raises(cdyn.InputError, match="Q1"):
        cdyn.FESpace(mesh, "Q1")
    with pytest.raises(cdyn.InputError, match="^solver: .*nope"):
        cdyn.step_solver("nope")
    p = cdyn.scalar_wave(mesh, dirichlet_parts="all")
    with pytest.raises(cdyn.InputError, match="^scheme: .*leapfrog"):
        cdyn.time_scheme("leapfrog", p, cdyn.step_solver("pdas"), 1e-3)
    with pytest.raises(cdyn.InputError, match="^dt: must be positive"):
        cdyn.time_scheme("midpoint", p, cdyn.step_solver("pdas"), -1.0)
    with pytest.raises(cdyn.InputError, match="no_such_part"):
        cdyn.DirichletLift(p.W, ["no_such_part"])
    with pytest.raises(cdyn.InputError, match="no_such.geo"):
        cdyn.read_mesh("no_such.geo")
    with pytest.raises(TypeError, match="unknown option 'tl'"):
        cdyn.QPOptions(tl=1e-12)


def test_a_qp_that_does_not_converge_is_a_numerical_error():
    p = cdyn.scalar_wave(cdyn.unit_square_mesh(6), f=-50.0, dirichlet_parts="all")
    qp = cdyn.BoundQP(S=p.A, r=p.load(0.0), lower=p.lower)
    with pytest.raises(cdyn.NumericalError, match="pgs"):
        cdyn.step_solver("pgs", cdyn.QPOptions(max_iterations=2)).solve(qp)
    result = cdyn.step_solver("pgs", cdyn.QPOptions(max_iterations=2, throw_on_failure=False)).solve(qp)
    assert not result.converged and result.kkt_residual > 1e-10


def test_a_python_error_in_a_datum_propagates():
    def f(x, y, t):
        raise ZeroDivisionError("in f")
    p = cdyn.scalar_wave(cdyn.unit_square_mesh(2), f=f)
    with pytest.raises(ZeroDivisionError, match="in f"):
        p.load(0.0)  # (a constant load is assembled when first asked for)
    with pytest.raises(TypeError):
        cdyn.run(42)
    assert np.isfinite(cdyn.scalar_wave(cdyn.unit_square_mesh(2), f=lambda x, y, t: x * y).load(0.0)).all()


def test_a_callable_datum_sees_z_on_a_3d_mesh(scene):
    # f(x, y, z, t) is evaluated at the point in space; f(x, y, t), which cannot see z,
    # is refused there instead of being evaluated as if z were 0.
    mesh = cdyn.read_mesh(os.path.join(os.path.dirname(scene("membrane_3d")), "..", "geo", "box.geo"))
    by_expression = cdyn.scalar_wave(mesh, f="x + 2*y + 3*z").load(0.0)
    by_callable = cdyn.scalar_wave(mesh, f=lambda x, y, z, t: x + 2 * y + 3 * z).load(0.0)
    assert np.abs(by_callable - by_expression).max() <= 1e-15 * np.abs(by_expression).max()
    with pytest.raises(cdyn.InputError, match=r"^f: a callable f\(x, y, t\) cannot depend on z"):
        cdyn.scalar_wave(mesh, f=lambda x, y, t: x).load(0.0)


def test_the_petsc_back_end_is_the_command_lines():
    # The PETSc back end ends its process without the interpreter's own ending
    # (docs/distributed.md): refused here, naming the key.
    with pytest.raises(cdyn.InputError, match=r"^solver.backend: the Python module runs on the native back end"):
        cdyn.run(set={"solver.backend": "petsc", "time.T": 0.01})
