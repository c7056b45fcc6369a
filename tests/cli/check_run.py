#!/usr/bin/env python3
"""check_run.py — `cdyn run` writes what docs/outputs.md promises, and the numbers agree.

Usage: check_run.py CDYN WORKDIR

Runs the default scene as it is (every output file: history.csv, summary.json,
scene.toml, fields.pvd + fields/*.vtu, plots/*.png when a python3 with matplotlib is
there, else a note), then on a small mesh (the --set overrides are part of what is
tested: the run must reflect them) and checks: history.csv has one row per step plus
the initial state, E_total = E_kin + E_pot on every row, summary.json's fields equal
what history.csv gives (E0, E_final, E_rel_drift, n_steps), n_dofs is that of P1+ on
the overridden mesh, the scene.toml written reruns the same run, output.fields and
output.plots switch their outputs off, and backward Euler never increases the energy.
Only the standard library is used (check_fields.py reads the VTU files).
"""
import csv
import glob
import json
import os
import re
import shutil
import subprocess
import sys

from cli_helpers import have_matplotlib

cdyn, work = sys.argv[1], sys.argv[2]


def run(out, *sets, scene=None, quiet=True, env=None):
    args = [cdyn, "run"] + ([scene] if scene else []) + ["--out", out] + (["--quiet"] if quiet else [])
    for s in sets:
        args += ["--set", s]
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.run(args, check=True, stdout=subprocess.PIPE, text=True, env=env)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return rows, summary, p.stdout



def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


# The default scene as it is: the seed's membrane, n = 20, 800 steps, fields every 20.
out = os.path.join(work, "run_default")
rows, s, stdout = run(out, quiet=False)
for f in ["history.csv", "summary.json", "scene.toml", "fields.pvd"]:
    assert os.path.isfile(os.path.join(out, f)), f
assert s["n_dofs"] == 21 ** 2 + 2 * 20 * 20 and s["n_steps"] == 800 == len(rows) - 1, (s["n_dofs"], s["n_steps"])
vtus = sorted(glob.glob(os.path.join(out, "fields", "step_*.vtu")))
assert len(vtus) == 800 // 20 + 1, len(vtus)
with open(os.path.join(out, "fields.pvd")) as f:
    pvd = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', f.read())
assert [os.path.join(out, f) for _, f in pvd] == vtus, pvd[:3]
times = {int(r["step"]): float(r["t"]) for r in rows}
for t, f in pvd:  # each file at the time of its step in history.csv
    assert float(t) == times[int(f[len("fields/step_"):-len(".vtu")])], (t, f)
if have_matplotlib():
    for png in ["energy.png", "probes.png", "contact.png"]:
        assert os.path.getsize(os.path.join(out, "plots", png)) > 1000, png
else:
    assert "Note: no plots" in stdout, stdout
print(stdout.strip().splitlines()[1])

# No python3 at all: one note, no plots, and the run succeeds.
out = os.path.join(work, "run_no_python")
env = dict(os.environ, CDYN_PYTHON="/nonexistent/python3")
rows, s, stdout = run(out, "mesh.n=4", "time.T=0.01", "output.fields=false", quiet=False, env=env)
assert "Note: no plots (no python3 found)" in stdout, stdout
assert not os.path.exists(os.path.join(out, "plots")) and not os.path.exists(os.path.join(out, "fields.pvd"))

n = 6
out = os.path.join(work, "run_midpoint")
rows, s, _ = run(out, f"mesh.n={n}", "time.T=0.05", "time.dt=0.001", "output.plots=false")
assert len(rows) == s["n_steps"] + 1 == 51, (len(rows), s["n_steps"])
assert s["n_dofs"] == (n + 1) ** 2 + 2 * n * n, s["n_dofs"]  # P1+ : vertices + one bubble per cell
assert s["pair"] == "P1+/P0" and s["scheme"] == "midpoint" and s["solver"] == "pdas"
for r in rows:
    ek, ep, et = float(r["E_kin"]), float(r["E_pot"]), float(r["E_total"])
    assert close(et, ek + ep, 1e-15), r  # printed with 17 digits: one rounding
E = [float(r["E_total"]) for r in rows]
assert close(s["E0"], E[0], 1e-15) and close(s["E_final"], E[-1], 1e-15)
drift = max(abs(e - E[0]) / abs(E[0]) for e in E)
assert close(s["E_rel_drift"], drift, 1e-9), (s["E_rel_drift"], drift)
for key in ["scene", "pair", "scheme", "solver", "n_dofs", "n_steps", "dt", "h", "E0", "E_final", "E_rel_drift",
            "max_violation", "setup_s", "wall_s", "s_per_step", "qp_iters_mean", "wellposed"]:
    assert key in s, key
assert s["wellposed"]["satisfied"] is True and s["wellposed"]["beta"] > 0
assert {"u@centre", "v@centre", "lambda@centre"} <= set(rows[0])
assert list(rows[0])[:8] == "step,t,E_kin,E_pot,E_total,active,qp_iters,solve_s".split(","), list(rows[0])

# The midpoint rule reconstructs its full steps (eq. 14): the reconstruction's cost is a
# part of each step besides the step QP, so solve_s + reconstruction_s <= step_s (three
# timers of one process, the last around the other two; printed with 17 digits), and
# each reconstruction solves its QP at least once; summary.json's figures are the
# column's mean and the QP iterations a step.
steps = rows[1:]
assert list(rows[0])[8:10] == ["step_s", "reconstruction_s"], list(rows[0])
for r in steps:
    solve, rec, step = float(r["solve_s"]), float(r["reconstruction_s"]), float(r["step_s"])
    assert 0 < rec and solve + rec <= step, (r["step"], solve, rec, step)
assert close(s["reconstruction_s_per_step"], sum(float(r["reconstruction_s"]) for r in steps) / len(steps), 1e-12)
assert s["reconstruction_iters_mean"] >= 1 and s["full_steps"] == "reconstructed", s

# The scene.toml written next to the results reruns the same run.
rerun_rows, rerun, _ = run(os.path.join(work, "run_rerun"), scene=os.path.join(out, "scene.toml"))
assert rerun["n_dofs"] == s["n_dofs"] and rerun["n_steps"] == s["n_steps"] and rerun["E_final"] == s["E_final"]

# Every step QP was solved: the largest KKT residual is within the scene's tolerance.
assert 0 <= s["kkt_residual_max"] <= s["solver_tol"], (s["kkt_residual_max"], s["solver_tol"])

# solver.condense = false (the bubbles kept in the step QP) and solver.cg_iterations = 0
# (pdas without CG) solve the same steps another way: the same energies, to the
# round-off that the midpoint scheme carries forward (test_condensation.cpp measures
# 4e-11 relative over its loops; 1e-9 leaves room on this longer run).
for variant in ["solver.condense=false", "solver.cg_iterations=0"]:
    v_rows, v, _ = run(os.path.join(work, "run_" + variant.split("=")[0]), f"mesh.n={n}", "time.T=0.05",
                       "time.dt=0.001", "output.fields=false", "output.plots=false", variant)
    for a, b in zip(rows, v_rows):
        assert abs(float(a["E_total"]) - float(b["E_total"])) <= 1e-9 * abs(s["E0"]), (variant, a["step"])

out = os.path.join(work, "run_backward_euler")
rows, s, _ = run(out, f"mesh.n={n}", "time.T=0.1", "time.dt=0.002", "time.scheme=backward_euler",
                 "output.fields=false", "output.plots=false")
assert s["scheme"] == "backward_euler" and s["n_steps"] == 50
# (backward Euler constrains U^{n+1} itself: no reconstruction, no column, no figure)
assert s["full_steps"] == "solved" and "reconstruction_s" not in rows[0] and "reconstruction_s_per_step" not in s
E = [float(r["E_total"]) for r in rows]
assert all(b <= a + 1e-13 * abs(E[0]) for a, b in zip(E, E[1:])), "backward Euler increased the energy"
assert E[-1] < E[0]
print("check_run: ok")
