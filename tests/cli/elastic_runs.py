"""elastic_runs.py — what the elasticity command-line checks (check_elasticity.py,
check_ramp.py) share: running a scene with overrides and reading its summary.json,
history.csv and contact.csv, the area of a .geo's mesh, and the ok/FAIL report."""
import csv
import json
import os
import re
import subprocess

QUIET = ["--quiet", "--set", "output.fields=false", "--set", "output.plots=false"]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def read_csv(path):
    with open(path, newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def run(cdyn, scene, out, *sets):
    """`cdyn run SCENE --out OUT --set ...` → (summary, history rows, contact rows)."""
    args = [cdyn, "run", scene, "--out", out] + QUIET
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    contact = os.path.join(out, "contact.csv")
    return summary, read_csv(os.path.join(out, "history.csv")), read_csv(contact) if os.path.isfile(contact) else []


def area(cdyn, mesh):
    """|Ω_h| of a .geo or .msh, from `cdyn mesh`."""
    text = subprocess.run([cdyn, "mesh", mesh], check=True, stdout=subprocess.PIPE, text=True).stdout
    return float(re.search(r"area\s+([0-9.eE+-]+)", text).group(1))
