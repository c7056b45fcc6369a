#!/usr/bin/env python3
"""check_study.py — `cdyn study` runs the product of its variations and measures them.

Usage: check_study.py CDYN WORKDIR

A study of the default scene on a 4 x 4 mesh over three dt values must give three
runs and three rows of study.csv with the documented columns (docs/outputs.md); the
finest run (smallest dt) is the reference, with an empty error; the others' error is
|u@centre(T) - u@centre_finest(T)| / |u@centre_finest(T)| from the runs' history.csv,
and E_rel_error_T = |J(T) - J0|/|J0| from their summary.json; work_precision.png is
written when a python3 with matplotlib is there.  A second study over two keys checks
the product (4 runs, the last --vary fastest).  Only the standard library is used.
"""
import csv
import json
import os
import shutil
import subprocess
import sys

from cli_helpers import have_matplotlib

cdyn, work = sys.argv[1], sys.argv[2]
COLUMNS = ["n_dofs", "n_steps", "dt", "h", "wall_s", "s_per_step", "qp_iters_mean", "E_rel_drift", "E_rel_error_T",
           "error", "error_kind"]


def study(out, *args):
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.run([cdyn, "study", "--out", out, "--set", "mesh.n=4", "--set", "time.T=0.02"] + list(args),
                       check=True, stdout=subprocess.PIPE, text=True)
    with open(os.path.join(out, "study.csv"), newline="") as f:
        reader = csv.DictReader(f)
        return reader.fieldnames, list(reader), p.stdout



def last_row(run_dir):
    with open(os.path.join(run_dir, "history.csv")) as f:
        return list(csv.DictReader(f))[-1]


out = os.path.join(work, "study_dt")
header, rows, stdout = study(out, "--vary", "time.dt=0.004,0.002,0.001")
print(stdout)
assert header[0] == "time.dt" and header[1:1 + len(COLUMNS)] == COLUMNS, header
assert [r["time.dt"] for r in rows] == ["0.004", "0.002", "0.001"]
assert [int(r["n_steps"]) for r in rows] == [5, 10, 20]
finest = rows[2]
assert finest["error"] == "" and finest["error_kind"] == "reference", finest
u_ref = float(last_row(os.path.join(out, finest["run"]))["u@centre"])
for r in rows:
    with open(os.path.join(out, r["run"], "summary.json")) as f:
        s = json.load(f)
    assert float(r["dt"]) == s["dt"] and int(r["n_dofs"]) == s["n_dofs"] == 5 ** 2 + 2 * 16
    assert float(r["E_rel_error_T"]) == abs(s["E_final"] - s["E0"]) / abs(s["E0"])
    if r is not finest:
        u = float(last_row(os.path.join(out, r["run"]))["u@centre"])
        assert r["error_kind"] == "finest" and float(r["error"]) == abs(u - u_ref) / abs(u_ref), (r, u, u_ref)
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
print("check_study: ok")
