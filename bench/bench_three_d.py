#!/usr/bin/python3
"""bench_three_d.py — the cost of a 3D elastodynamic contact step against the number of
unknowns, with the Cholesky factor and with the CG path (docs/performance.md, "Three
dimensions").

Usage: bench_three_d.py CDYN SOURCE_DIR OUT_DIR [--sizes 8,16,24,32] [--methods NAME,...] [--linear factor,cg]

The scene: data/scenes/cube_3d.toml, the unit cube (n³ cells of six tetrahedra) falling
at v0 = 0.1 onto the plane z = −h/2 (E = 1, ν = 0.3, ρ = 1; its face "bottom" may
not cross it), dt = h/2 (about the time a pressure wave takes to cross half a cell:
dt ∝ h keeps the step matrix's condition number bounded).  It runs 16 steps: contact
from step 6 on.  Figures, each the mean over the window of history.csv's step_s (the
whole step):
  - contact: steps 6–16 (the impact and the contact that follows);
  - linear: the same steps of the same run with obstacle.enabled = false;
  - setup: the wall time of the process less its steps (reading, assembly, the mass
    model, condition (12), the outputs);
  - peak memory (the maximum resident set size, /usr/bin/time).
One core (OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = 1), fields and plots off.  The
exponent of the per-step cost against the unknowns is fitted by least squares on
log-log over the sizes.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys

METHODS = {
    "P1/P1 backward_euler": ["method.pair=P1/P1", "time.scheme=backward_euler"],
    "P1+/P0 midpoint": ["method.pair=P1+/P0", "time.scheme=midpoint"],
}
WINDOW = (6, 16)
SCENE = ""


def scene(n):
    h = 1.0 / n
    return [f"mesh.n={n}", f"obstacle.point=[0, 0, {-h / 2!r}]", f"time.dt={h / 2!r}", f"time.T={16 * h / 2!r}",
            "output.probes={}", "output.wellposed=false"]


def run(cdyn, out, sets):
    args = ["/usr/bin/time", "-f", "peak_kB %M wall_s %e", cdyn, "run", SCENE, "--out", out, "--quiet",
            "--set", "output.fields=false", "--set", "output.plots=false"]
    for s in sets:
        args += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    p = subprocess.run(args, check=True, env=env, stderr=subprocess.PIPE, text=True)
    peak_kB = int(re.search(r"peak_kB (\d+)", p.stderr).group(1))
    wall = float(re.search(r"wall_s ([0-9.]+)", p.stderr).group(1))
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    steps = [float(r["step_s"]) for r in rows if WINDOW[0] <= int(r["step"]) <= WINDOW[1]]
    active = max(int(r["active"]) for r in rows)
    setup = wall - sum(float(r["step_s"]) for r in rows)
    return sum(steps) / len(steps), setup, peak_kB, summary, active


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cdyn")
    ap.add_argument("source")
    ap.add_argument("out")
    ap.add_argument("--sizes", default="8,16,24,32")
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--linear", default="factor,cg")
    a = ap.parse_args()
    global SCENE
    SCENE = os.path.join(a.source, "data", "scenes", "cube_3d.toml")
    sizes = [int(s) for s in a.sizes.split(",")]
    print("| method | linear | n | unknowns | contact step (s) | linear step (s) | ratio | ns/unknown/step | setup (s) "
          "| peak memory (MB) | max active |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for method in a.methods.split(","):
        for linear in a.linear.split(","):
            points = []
            for n in sizes:
                sets = scene(n) + METHODS[method] + [f"solver.linear={linear}"]
                tag = f"{method.split()[0].replace('/', '_').replace('+', 'b')}_{linear}_{n}"
                try:
                    c, setup, peak, summary, active = run(a.cdyn, os.path.join(a.out, tag), sets)
                    l, _, _, _, _ = run(a.cdyn, os.path.join(a.out, tag + "_linear"), sets + ["obstacle.enabled=false"])
                except subprocess.CalledProcessError as e:
                    print(f"| {method} | {linear} | {n} | failed: {e.stderr.strip().splitlines()[-1]} |")
                    continue
                N = summary["n_free"]
                points.append((N, c))
                print(f"| {method} | {linear} | {n} | {N} | {c:.4g} | {l:.4g} | {c / l:.2f} | {1e9 * c / N:.0f} "
                      f"| {setup:.3g} | {peak / 1024:.0f} | {active} |", flush=True)
            if len(points) >= 2:
                xs = [math.log(N) for N, _ in points]
                ys = [math.log(c) for _, c in points]
                mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
                slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
                print(f"|  {method} | {linear} | exponent of the contact step | {slope:.2f} |")


if __name__ == "__main__":
    sys.exit(main())
