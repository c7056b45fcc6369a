#!/usr/bin/env python3
"""check_study.py — `cdyn study` runs the product of its variations and measures them.

Usage: check_study.py CDYN WORKDIR

A study of the default scene on a 4 x 4 mesh over three dt values must give three
runs and three rows of study.csv with the documented columns (docs/outputs.md); the
finest run (smallest dt) is the reference, with an empty error; the others' error
(the default measure, probe:centre:u) is max over their steps of
|u@centre(t) - u@centre_finest(t)| / max_t |u@centre_finest(t)| from the runs'
history.csv, and E_rel_error_T = |J(T) - J0|/E_scale from their summary.json;
work_precision.png is written when a python3 with matplotlib is there; the runs write
no field files (--fields asks for them).  A second study over two keys checks the
product (4 runs, the last --vary fastest).  Then the measures of --error: the first
probe as the scene writes it (not the first by name), a probe's lambda column, the
energy drift, and the Hertz scene (elasticity, J0 = 0), whose default error is its
probe's displacement vector against the finest run (before: the final energy against
the finest run's, a near-zero reference).  Only the standard library is used.
"""
import csv
import json
import os
import shutil
import subprocess
import sys

from cli_helpers import have_matplotlib

cdyn, work = sys.argv[1], sys.argv[2]
hertz = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "scenes", "hertz.toml")
COLUMNS = ["n_dofs", "n_steps", "dt", "h", "wall_s", "s_per_step", "qp_iters_mean", "E_rel_drift", "E_rel_error_T",
           "error", "error_kind", "error_measure", "partial", "run"]


def study(out, *args, scene=None, plot=False):
    """study.csv's header and rows, and stdout.  Without plot, no python is started
    (CDYN_PYTHON names none: a note instead of the plot, a second saved per study)."""
    shutil.rmtree(out, ignore_errors=True)
    base = ["--set", "mesh.n=4", "--set", "time.T=0.02"] if scene is None else [scene]
    env = None if plot else dict(os.environ, CDYN_PYTHON="/nonexistent/python3")
    p = subprocess.run([cdyn, "study", "--out", out] + base + list(args),
                       check=True, stdout=subprocess.PIPE, text=True, env=env)
    with open(os.path.join(out, "study.csv"), newline="") as f:
        reader = csv.DictReader(f)
        return reader.fieldnames, list(reader), p.stdout



def history(run_dir):
    with open(os.path.join(run_dir, "history.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def history_error(rows, ref, columns):
    """max over the rows of |c(t) - c_ref(t)| / max_t |c_ref(t)|, c_ref linear in t."""
    def norm(values):
        return sum(v * v for v in values) ** 0.5

    amplitude = max(norm([r[c] for c in columns]) for r in ref)
    worst = 0.0
    for r in rows:
        t = r["t"]
        k = max([i for i in range(len(ref)) if ref[i]["t"] <= t] or [0])
        k1 = min(k + 1, len(ref) - 1)
        w = 0.0 if k1 == k else (t - ref[k]["t"]) / (ref[k1]["t"] - ref[k]["t"])
        worst = max(worst, norm([r[c] - ((1 - w) * ref[k][c] + w * ref[k1][c]) for c in columns]))
    return worst / amplitude


out = os.path.join(work, "study_dt")
header, rows, stdout = study(out, "--vary", "time.dt=0.004,0.002,0.001", plot=True)
print(stdout)
assert header[0] == "time.dt" and header[1:] == COLUMNS, header
assert [r["time.dt"] for r in rows] == ["0.004", "0.002", "0.001"]
assert [int(r["n_steps"]) for r in rows] == [5, 10, 20]
assert all(r["error_measure"] == "probe:centre:u" and r["partial"] == "false" for r in rows), rows
finest = rows[2]
assert finest["error"] == "" and finest["error_kind"] == "reference", finest
ref = history(os.path.join(out, finest["run"]))
for r in rows:
    with open(os.path.join(out, r["run"], "summary.json")) as f:
        s = json.load(f)
    assert float(r["dt"]) == s["dt"] and int(r["n_dofs"]) == s["n_dofs"] == 5 ** 2 + 2 * 16
    assert float(r["E_rel_error_T"]) == abs(s["E_final"] - s["E0"]) / s["E_scale"]
    assert not os.path.exists(os.path.join(out, r["run"], "fields.pvd")), "a study run wrote fields without --fields"
    if r is not finest:
        e = history_error(history(os.path.join(out, r["run"])), ref, ["u@centre"])
        assert r["error_kind"] == "finest" and abs(float(r["error"]) - e) <= 1e-9 * e, (r, e)
        assert float(r["error"]) > 0
if have_matplotlib():
    assert os.path.getsize(os.path.join(out, "work_precision.png")) > 1000
else:
    assert "Note: no work-precision plot" in stdout, stdout

out = os.path.join(work, "study_product")
header, rows, _ = study(out, "--vary", "time.scheme=midpoint,backward_euler", "--vary", "time.dt=0.004,0.002")
assert header[:2] == ["time.scheme", "time.dt"], header
assert [(r["time.scheme"], r["time.dt"]) for r in rows] == [
    ("midpoint", "0.004"), ("midpoint", "0.002"), ("backward_euler", "0.004"), ("backward_euler", "0.002")], rows
assert [r["run"] for r in rows] == ["run_000", "run_001", "run_002", "run_003"]
assert sum(r["error_kind"] == "reference" for r in rows) == 1  # the first of the two dt = 0.002 runs

# --fields: the runs write their field series.
out = os.path.join(work, "study_fields")
header, rows, _ = study(out, "--vary", "time.dt=0.004,0.002", "--fields")
assert all(os.path.isfile(os.path.join(out, r["run"], "fields.pvd")) for r in rows)

# The first probe as written (zeta), not the first by name (alpha); history.csv's columns
# in the same order; an explicit probe column; the energy measure.
probes = ["--set", "output.probes={ zeta = [0.5, 0.5], alpha = [0.25, 0.25] }"]
out = os.path.join(work, "study_probes")
header, rows, _ = study(out, "--vary", "time.dt=0.004,0.002", *probes)
assert [r["error_measure"] for r in rows] == ["probe:zeta:u"] * 2, rows
with open(os.path.join(out, "run_000", "history.csv")) as f:
    columns = f.readline().strip().split(",")
assert [c for c in columns if "@" in c] == ["u@zeta", "v@zeta", "lambda@zeta", "u@alpha", "v@alpha", "lambda@alpha"], columns
e = history_error(history(os.path.join(out, "run_000")), history(os.path.join(out, "run_001")), ["u@zeta"])
assert abs(float(rows[0]["error"]) - e) <= 1e-9 * e, (rows[0], e)
header, rows, _ = study(out, "--vary", "time.dt=0.004,0.002", "--error", "probe:alpha:v", *probes)
e = history_error(history(os.path.join(out, "run_000")), history(os.path.join(out, "run_001")), ["v@alpha"])
assert rows[0]["error_measure"] == "probe:alpha:v" and abs(float(rows[0]["error"]) - e) <= 1e-9 * e, (rows[0], e)
header, rows, _ = study(out, "--vary", "time.dt=0.004,0.002", "--error", "energy")
for r in rows:
    with open(os.path.join(out, r["run"], "summary.json")) as f:
        s = json.load(f)
    assert r["error_kind"] == "energy" and float(r["error"]) == s["E_rel_drift"], (r, s["E_rel_drift"])

# Elasticity from rest (Hertz): the probe's displacement vector (ux, uy) against the
# finest run, an error below 1 (the release at t = 0.5 falls in a step of the coarse run:
# measured 0.55), where the old measure, the final energy against J_finest(T) = 0.0099
# (the rest after energies of 60 under the load), compared round-off-sized remnants.
out = os.path.join(work, "study_hertz")
header, rows, stdout = study(out, "--vary", "time.dt=0.1,0.05", scene=hertz)
assert [r["error_measure"] for r in rows] == ["probe:bottom:u"] * 2, rows
e = history_error(history(os.path.join(out, "run_000")), history(os.path.join(out, "run_001")),
                  ["ux@bottom", "uy@bottom"])
assert rows[0]["error_kind"] == "finest" and abs(float(rows[0]["error"]) - e) <= 1e-9 * e < 1, (rows[0], e)
assert "warning: time.dt = 0.1 is" in stdout, stdout  # the runs' warnings, in the study's lines
print("check_study: ok")
