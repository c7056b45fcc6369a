"""cli_helpers.py — what the command-line checks share: running a scene with overrides
and reading its summary.json, history.csv and contact.csv, the area of a mesh, the
ok/FAIL report (check_elasticity.py, check_ramp.py), Hertz's contact zone and pressure
(check_elasticity.py, check_obstacles.py), whether cdyn will find
matplotlib for its plots (check_run.py, check_study.py), and meshio for the checks that
read the field files (check_fields.py, check_materials.py)."""
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys

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


def check_hertz_zone(name, loaded, a, P):
    """Hertz's half-width a lies between the last vertex in contact and the next one on
    each side (the nodal contact zone can only end at a vertex)."""
    for side in (1, -1):
        zone = sorted((r for r in loaded if side * r["x"] >= 0), key=lambda r: side * r["x"])
        inside = max(side * r["x"] for r in zone if r["force"] > 1e-9 * P)
        outside = min(side * r["x"] for r in zone if side * r["x"] > inside)
        check(inside <= a <= outside, f"{name} side {side:+d}: a = {a:.4f} mm in [{inside:.4f}, {outside:.4f}]")


def hertz_pressure_deviation(rows, a, P):
    """max |p_h − p| / p0 over the given vertices, p(x) = p0 √(a² − x²)/a, p0 = 2P/(π a)."""
    p0 = 2 * P / (math.pi * a)
    return max(abs(r["pressure"] - p0 * math.sqrt(max(a * a - r["x"] ** 2, 0.0)) / a) for r in rows) / p0, p0


def area(cdyn, mesh):
    """|Ω_h| of a .geo or .msh, from `cdyn mesh`."""
    text = subprocess.run([cdyn, "mesh", mesh], check=True, stdout=subprocess.PIPE, text=True).stdout
    return float(re.search(r"area\s+([0-9.eE+-]+)", text).group(1))


def import_meshio(check_name):
    """(meshio, numpy), or exit status 77 (the test is skipped) when either is missing."""
    try:
        import meshio
        import numpy
    except ImportError:
        print(f"{check_name}: skipped (python3-meshio or numpy missing)")
        sys.exit(77)
    return meshio, numpy


def have_matplotlib():
    """Whether cdyn will find a python3 with matplotlib (python_script.cpp's search)."""
    for python in ["python3", "/usr/bin/python3"]:
        if shutil.which(python) and subprocess.run([python, "-c", "import matplotlib"],
                                                   stderr=subprocess.DEVNULL).returncode == 0:
            return True
    return False
