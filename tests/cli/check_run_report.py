#!/usr/bin/env python3
"""check_run_report.py — what a run says about itself (docs/outputs.md): the energy
drift of a run from rest, its warnings, how much it wrote, and the output defaults.

Usage: check_run_report.py CDYN SOURCE_DIR WORKDIR

- The Hertz scene starts at rest (J0 = 0): summary.json's E_rel_drift is a number, not
  null, equal to E_abs_drift / E_scale with E_abs_drift = max |J - J0 - W| (W the
  work of its traction in t, history.csv's data_work) and
  E_scale = max(|J0|, max(E_kin + |E_pot|)/2) from history.csv, and the paragraph
  prints no "inf"; a run with energy (the membrane) keeps E_scale = |J0|, so that
  E_rel_drift is DESIGN.md's max |J - J0|/|J0|.
- Warnings, printed on stderr ("cdyn: warning: ...") and listed in summary.json: a T
  that is no multiple of dt (the steps and the time reached), a step far above the
  time a wave takes to cross a cell (dt = T on the membrane, one step), none for the
  default scene.
- summary.json's "written" gives the bytes of each file and of the field series, as on
  disk, and the paragraph names them.
- Without output.every / output.contact_every a run writes about 100 to 200 frames
  (every = floor(n_steps/100)): 501 steps give 101 field files, the disk's 200 steps
  101 contact.csv frames.
Only the standard library is used.
"""
import csv
import json
import os
import shutil
import subprocess
import sys

from cli_helpers import check, failures

cdyn, src, work = sys.argv[1:4]
scenes = os.path.join(src, "data", "scenes")
os.makedirs(work, exist_ok=True)


def run(out, *sets, scene=None):
    out = os.path.join(work, out)
    shutil.rmtree(out, ignore_errors=True)
    args = [cdyn, "run"] + ([scene] if scene else []) + ["--out", out, "--set", "output.plots=false"]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, check=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "history.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    return out, summary, rows, p.stdout, p.stderr


def drift(rows):
    J0 = rows[0]["E_total"]
    absolute = max(abs(r["E_total"] - J0 - r.get("data_work", 0.0)) for r in rows)
    scale = max(abs(J0), max(r["E_kin"] + abs(r["E_pot"]) for r in rows) / 2)
    return absolute, scale


# --- the energy drift from rest -----------------------------------------------------
out, s, rows, stdout, stderr = run("hertz", scene=os.path.join(scenes, "hertz.toml"))
absolute, scale = drift(rows)
check(s["E0"] == 0 and isinstance(s["E_rel_drift"], float), f"hertz: J0 = 0 and E_rel_drift = {s['E_rel_drift']}")
check(s["E_abs_drift"] == absolute and s["E_scale"] == scale and scale > 0,
      f"hertz: E_abs_drift {s['E_abs_drift']:.6g} and E_scale {s['E_scale']:.6g} as history.csv gives them")
check(s["E_rel_drift"] == s["E_abs_drift"] / s["E_scale"], "hertz: E_rel_drift = E_abs_drift / E_scale")
check("inf" not in stdout and "E_scale" in stdout, "hertz: the paragraph prints the drift against E_scale, no inf")
out, s, rows, stdout, stderr = run("membrane", "mesh.n=6", "time.T=0.05")
absolute, scale = drift(rows)
check(s["E_scale"] == abs(s["E0"]) == scale and s["E_rel_drift"] == absolute / abs(s["E0"]),
      "membrane: E_scale = |J0|, E_rel_drift = max |J - J0|/|J0|")
check("max |J - J0|/|J0| = " in stdout, "membrane: the paragraph prints max |J - J0|/|J0|")

# --- warnings --------------------------------------------------------------------------
check(s["warnings"] == [] and stderr == "", f"membrane: no warning ({s['warnings']}, {stderr!r})")
out, s, rows, stdout, stderr = run("T_not_multiple", "mesh.n=6", "time.T=0.0105")
w = "time.T = 0.0105 is not a multiple of time.dt = 0.001: 11 steps, to t = 0.011"
check(s["warnings"] == [w] and stderr == f"cdyn: warning: {w}\n" and s["n_steps"] == 11,
      f"T no multiple of dt: {s['warnings']}")
out, s, rows, stdout, stderr = run("dt_is_T", "time.dt=0.8")
check(len(s["warnings"]) == 1 and s["warnings"][0].startswith("time.dt = 0.8 is 11.3 times h/c = 0.0707")
      and stderr.startswith("cdyn: warning: time.dt = 0.8") and s["n_steps"] == 1, f"dt = T: {s['warnings']}")

# --- what was written ------------------------------------------------------------------
out, s, rows, stdout, stderr = run("written", "mesh.n=6", "time.T=0.05", "output.every=10")
on_disk = {f: os.path.getsize(os.path.join(out, f)) for f in ("scene.toml", "history.csv")}
on_disk["fields"] = os.path.getsize(os.path.join(out, "fields.pvd")) + sum(
    os.path.getsize(os.path.join(out, "fields", f)) for f in os.listdir(os.path.join(out, "fields")))
on_disk["total"] = sum(on_disk.values())
check(s["written"] == on_disk, f"written: {s['written']} as on disk {on_disk}")
check("history.csv " in stdout and "fields " in stdout, "the paragraph says what was written")

# --- output defaults -------------------------------------------------------------------
scene = os.path.join(work, "no_every.toml")
with open(scene, "w") as f:
    f.write('[mesh]\nkind = "unit_square"\nn = 4\n[physics]\nmodel = "membrane"\nf = "-1"\n'
            '[dirichlet]\nparts = "all"\nvalue = "0.02"\n[initial]\nu = "0.02"\n[time]\ndt = 0.001\nT = 0.501\n')
out, s, rows, stdout, stderr = run("default_every", scene=scene)
frames = len(os.listdir(os.path.join(out, "fields")))
check(s["n_steps"] == 501 and frames == 102, f"default output.every = 5: {frames} field files for 501 steps (0, 5, ..., 500, 501)")
out, s, rows, stdout, stderr = run("default_contact_every", "time.T=0.002", scene=os.path.join(scenes, "disk.toml"))
with open(os.path.join(out, "contact.csv")) as f:
    steps = {r["step"] for r in csv.DictReader(f)}
check(s["n_steps"] == 200 and len(steps) == 101, f"default output.contact_every = 2: {len(steps)} contact.csv frames for 200 steps")

if failures:
    sys.exit("check_run_report: FAILED: " + "; ".join(failures))
print("check_run_report: ok")
