"""cdyn.run, study, wellposed and simulation against the `cdyn` program: the same code,
so the same numbers bit for bit (history.csv's 17 digits read back exactly), except the
timings."""

import json
import os
import tomllib

import numpy as np
import pytest

import cdyn

# What differs from run to run: the clocks (step_s: a history column on main since the
# work of data in t) and the bytes written (history.csv holds the clocks).
TIMINGS = {"solve_s", "step_s", "reconstruction_s", "setup_s", "wall_s", "s_per_step", "qp_s_per_step",
           "reconstruction_s_per_step", "fields_s", "written"}
SMALL = ["mesh.n=8", "time.T=0.4"]


def read_history(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
        return {name: col for name, col in zip(header, np.loadtxt(f, delimiter=",", ndmin=2).T)}


def same_history(a, b):
    assert list(a) == list(b)
    for name in a:
        if name not in TIMINGS:
            assert np.array_equal(a[name], b[name]), name


def same_summary(a, b):
    assert a.keys() == b.keys()
    for key in a:
        if key not in TIMINGS:
            assert a[key] == b[key], key


def test_default_run_is_the_command_lines(cli, tmp_path):
    status, _, err = cli("run", "--quiet", "--set", "output.plots=false", "--out", tmp_path / "cli")
    assert status == 0, err
    r = cdyn.run(out=tmp_path / "py")
    with open(tmp_path / "cli" / "summary.json") as f:
        summary = json.load(f)
    assert r["summary"]["E_rel_drift"] == summary["E_rel_drift"] > 0
    same_summary(r["summary"], summary)
    same_history(r["history"], read_history(tmp_path / "cli" / "history.csv"))
    assert r["history"]["step"].dtype.kind == "i" and r["history"]["step"][-1] == 800


def test_fields_are_the_field_files(tmp_path):
    r = cdyn.run(set=SMALL + ["output.every=10"], out=tmp_path)
    f, h = r["fields"], r["history"]
    assert list(f["step"]) == list(range(0, 401, 10))
    assert np.array_equal(f["t"], h["t"][f["step"]])
    assert f["u"].shape == (41, 81) and f["points"].shape == (81, 3) and f["cells"].shape == (128, 3)
    assert np.all(f["u"][0] == 0.02)
    # the probe at the centre (a vertex for n = 8, where the bubbles vanish) is the vertex
    # value of u; measured difference 0 (the P1 hat of the vertex is 1 there, the others 0)
    centre = int(np.argmin(np.hypot(f["points"][:, 0] - 0.5, f["points"][:, 1] - 0.5)))
    assert np.abs(f["u"][:, centre] - h["u@centre"][f["step"]]).max() <= 1e-15
    assert np.all(f["lambda"] <= 1e-14)  # λ ≤ 0 (round-off of either sign where inactive)


def test_a_dict_scene_is_its_file(scene, tmp_path):
    path = scene("lshape")
    with open(path, "rb") as f:
        as_dict = tomllib.load(f)
    # the dict's mesh.file is relative to the current directory (no scene file to be relative to)
    as_dict["mesh"]["file"] = os.path.join(os.path.dirname(path), as_dict["mesh"]["file"])
    small = {"time.T": 0.1, "output.fields": False}
    a = cdyn.run(as_dict, set=small, out=tmp_path / "dict")
    b = cdyn.run(path, set=["time.T=0.1", "output.fields=false"], out=tmp_path / "file")
    same_history(a["history"], b["history"])
    assert a["fields"] is None and a["summary"]["scene"] == b["summary"]["scene"] == "lshape"
    # probes keep the dict's order, as a file's
    assert [c for c in a["history"] if c.startswith("u@")] == ["u@corner", "u@middle"]


def test_stepping_the_simulation_by_hand_is_the_run(tmp_path):
    r = cdyn.run(set=SMALL, out=tmp_path)
    sim = cdyn.simulation(set=SMALL)
    s = sim.initial
    E = [sim.scheme.energy(s).total]
    for _ in range(sim.n_steps):
        sim.scheme.step(s)
        E.append(sim.scheme.energy(s).total)
    assert sim.n_steps == 400 and s.t == pytest.approx(0.4)
    assert np.array_equal(np.array(E), r["history"]["E_total"])


def test_study_is_the_command_lines(cli, scene, tmp_path):
    args = ["--vary", "time.scheme=midpoint,backward_euler", "--vary", "time.dt=0.02,0.01", "--set", "time.T=3.2"]
    status, _, err = cli("study", scene("oscillator"), *args, "--out", tmp_path / "cli")
    assert status == 0, err
    s = cdyn.study(scene("oscillator"), vary={"time.scheme": ["midpoint", "backward_euler"], "time.dt": [0.02, 0.01]},
                   set={"time.T": 3.2}, out=tmp_path / "py")
    table = cdyn.runs.read_csv(tmp_path / "cli" / "study.csv")
    assert list(s["table"]) == list(table) and len(s["runs"]) == 4
    for name, column in table.items():
        if name not in TIMINGS:
            assert np.array_equal(s["table"][name], column, equal_nan=column.dtype.kind == "f"), name
    assert s["table"]["error_measure"][0] == "probe:mass:u"


def test_wellposed_is_the_command_lines(cli):
    status, out, err = cli("wellposed", "--json", "--set", "mesh.n=6")
    assert status == 0, err
    rows = cdyn.wellposed(set={"mesh.n": 6})
    assert rows == json.loads(out)
    seed = next(r for r in rows if r["pair"] == "P1+/P0")
    assert seed["satisfied"] and seed["dim_ker_B"] == seed["N_g"] == 25


def test_scene_text_and_overrides():
    text = cdyn.scene_text(set={"mesh.n": 7, "time.scheme": "backward_euler", "output.probes": {"a": [0.25, 0.25]}})
    scene = tomllib.loads(text)
    assert scene["mesh"]["n"] == 7 and scene["time"]["scheme"] == "backward_euler"
    assert scene["output"]["probes"] == {"a": [0.25, 0.25]}
    assert tomllib.loads(cdyn.default_scene())["name"] == "membrane"
