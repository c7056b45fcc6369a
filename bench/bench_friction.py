#!/usr/bin/python3
"""bench_friction.py — the cost of friction (docs/friction.md, "Cost"): the mean wall
time of a step over the steps in contact, with Coulomb (or Tresca) friction against the
same scene frictionless, on the elastic disk (data/scenes/disk.toml), the disk
thrown at the 30° ramp (data/scenes/ramp.toml) and, in space, the plate sliding down an
incline of data/scenes/incline_block_3d.toml (two tangential unknowns a vertex).

Usage: bench_friction.py CDYN SOURCE_DIR OUT_DIR [--repeat R] [--solver pdas,pgs] [--scenes disk,ramp,plate3d]

Both runs use backward Euler (the scheme that takes friction with P1+/P0,
docs/friction.md) and the same step solver; the frictional run adds the rotation of
the contact nodes to (n, t) unknowns (the disk's plane is axis-aligned: frictionless it
needs none) and the semismooth Newton loop around the step solver, or projected
Gauss–Seidel with soft thresholds for pgs.  The target: at most 3 times the frictionless
contact step.  Each (scene, law) runs R times alternated with the frictionless run, so
that both see the same machine; the figure is the ratio of the means over the contact
window (steps with an active constraint, and the next) of history.csv's step_s.  One
core (OPENBLAS_NUM_THREADS=1), fields and plots off.
"""
import argparse
import csv
import json
import os
import subprocess

SCENES = {"disk": "disk.toml", "ramp": "ramp.toml", "plate3d": "prism_3d.toml"}
# In space: data/scenes/incline_block_3d.toml's plate sliding down the incline, built on
# prism_3d.toml (the same box.geo) so that the frictionless run has no friction keys.
SCENE_SETS = {"plate3d": ["mesh.set.h=0.25", "mesh.set.Ly=1.0", "mesh.set.Lz=0.25", "physics.E=1e8",
                          "physics.nu=0.3", "physics.rho=1000.0", "physics.gravity=[4.247855, 2.4525, -8.495709211]",
                          "obstacle.where=bottom", "obstacle.point=[0.0, 0.0, 0.0]", "obstacle.normal=[0.0, 0.0, 1.0]",
                          'initial.v=["0", "0", "0"]', "method.pair=P1/P0", "time.dt=1e-3", "time.T=0.1",
                          "output.probes={}"]}
LAWS = {
    "coulomb mu = 0.3": ['contact.friction="coulomb"', 'contact.mu="0.3"'],
    "tresca s = 0.5 N/mm^2": ['contact.friction="tresca"', 'contact.threshold="0.5"'],
}
COMMON = ["time.scheme=backward_euler", "output.fields=false", "output.plots=false"]


def run(cdyn, scene, out, sets):
    args = [cdyn, "run", scene, "--out", out, "--quiet"]
    for s in COMMON + sets:
        args += ["--set", s]
    subprocess.run(args, check=True, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        return rows, json.load(f)


def contact_window(rows):
    steps = [int(r["step"]) for r in rows if int(r["active"]) > 0]
    return (steps[0], steps[-1] + 1) if steps else (1, len(rows) - 1)


def mean_step(rows, window):
    w = [float(r["step_s"]) for r in rows if window[0] <= int(r["step"]) <= window[1]]
    return sum(w) / len(w)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cdyn")
    ap.add_argument("source")
    ap.add_argument("out")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--solver", default="pdas,pgs")
    ap.add_argument("--scenes", default="", help="a comma-separated subset of " + ",".join(SCENES))
    a = ap.parse_args()
    unknown = [n for n in a.scenes.split(",") if n and n not in SCENES]
    if unknown:
        ap.error(f"--scenes: unknown {', '.join(unknown)} (available: {', '.join(SCENES)})")
    print(f"{'scene':7} {'solver':6} {'law':24} {'frictionless ms':>16} {'friction ms':>12} {'ratio':>6} "
          f"{'QP iters':>9} {'W_f':>10}")
    for name, file in ((k, v) for k, v in SCENES.items() if not a.scenes or k in a.scenes.split(",")):
        scene = os.path.join(a.source, "data/scenes", file)
        for solver in a.solver.split(","):
            for law, sets in LAWS.items():
                t_free, t_fric = [], []
                for k in range(a.repeat):
                    base = os.path.join(a.out, f"{name}_{solver}_{k}")
                    own = SCENE_SETS.get(name, []) + [f"solver.name={solver}"]
                    free, _ = run(a.cdyn, scene, base + "_free", own)
                    fric, summary = run(a.cdyn, scene, base + "_friction", own + sets)
                    window = contact_window(free)
                    t_free.append(mean_step(free, window))
                    t_fric.append(mean_step(fric, window))
                f, g = sum(t_free) / len(t_free), sum(t_fric) / len(t_fric)
                print(f"{name:7} {solver:6} {law:24} {1e3 * f:16.4f} {1e3 * g:12.4f} {g / f:6.2f} "
                      f"{summary['qp_iters_mean']:9.2f} {summary['friction_work']:10.4g}")


if __name__ == "__main__":
    main()
