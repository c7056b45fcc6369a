#!/usr/bin/env python3
"""check_run.py — `cdyn run` writes what DESIGN.md §5 promises, and the numbers agree.

Usage: check_run.py CDYN WORKDIR

Runs the default scene on a small mesh (the --set overrides are part of what is
tested: the run must reflect them) and checks: history.csv has one row per step plus
the initial state, E_total = E_kin + E_pot on every row, summary.json's fields equal
what history.csv gives (E0, E_final, E_rel_drift, n_steps), n_dofs is that of P1+ on
the overridden mesh, and backward Euler never increases the energy.  Only the
standard library is used.
"""
import csv
import json
import os
import subprocess
import sys

cdyn, work = sys.argv[1], sys.argv[2]


def run(out, *sets):
    args = [cdyn, "run", "--quiet", "--out", out]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return rows, summary


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


n = 6
out = os.path.join(work, "run_midpoint")
rows, s = run(out, f"mesh.n={n}", "time.T=0.05", "time.dt=0.001")
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
            "max_violation", "wall_s", "s_per_step", "qp_iters_mean", "wellposed"]:
    assert key in s, key
assert s["wellposed"]["satisfied"] is True and s["wellposed"]["beta"] > 0
assert {"u@centre", "v@centre", "lambda@centre"} <= set(rows[0])

out = os.path.join(work, "run_backward_euler")
rows, s = run(out, f"mesh.n={n}", "time.T=0.1", "time.dt=0.002", "time.scheme=backward_euler")
assert s["scheme"] == "backward_euler" and s["n_steps"] == 50
E = [float(r["E_total"]) for r in rows]
assert all(b <= a + 1e-13 * abs(E[0]) for a, b in zip(E, E[1:])), "backward Euler increased the energy"
assert E[-1] < E[0]
print("check_run: ok")
