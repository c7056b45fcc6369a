#!/usr/bin/python3
"""bench_scaling.py — wall time per step against the number of dofs (docs/performance.md (c)).

The seed's membrane (data/scenes/membrane.toml: P1+/P0, midpoint, dt = 0.001) for
n = 40 … 640, each a whole `cdyn run` under /usr/bin/time -v: the time per step is the
time loop's (summary.json s_per_step, its QP part qp_s_per_step), the peak memory the
process's maximum resident set.  Two windows per n: by default the first 20 steps (no
contact yet: one forward/back solve per step, the floor of a step), and with --steps 270
the steps 1–270, which contain the impact at t ≈ 0.258: then the table adds the QP time
per step over the steps with an active constraint (history.csv's solve_s where
active > 0: PDAS iterations, CG solves, row updates and refactorizations as the contact
zone grows).  Prints a table (with the time per dof and step, which a step of O(N)
work would keep constant), the least-squares exponent p of time/step ∝ N^p over the
sizes (target p ≤ 1.2), with N the free dofs, and the exponents between consecutive sizes;
then the mean over steps 2.. (history.csv's step_s: without step 1's analysis and first
factorization) and its exponent from n = 160 to 640, the performance issue's range.

With --first 20 the same runs also give the mean of their first 20 steps (history.csv's
step_s: the step's own time, without the loop's output), so that one run per size
serves both windows.

With --resting the membrane starts on the obstacle (initial.u = 0): every step is a
contact step, most vertices active, the membrane lifting off slowly near the boundary
(docs/performance.md, "Contact in every regime") — the contact regime without the 257
steps of free flight that the impact run's mean is made of.  With --no-wellposed the
runs skip condition (12) (output.wellposed = false): its cost at these sizes is (f)'s
figure, not a step's, and at n = 640 it would be a minute of each run's set-up.
scripts/bench.sh: --steps 20 --no-wellposed (free flight, the floor of a step), then
--steps 30 --resting --no-wellposed.

Usage:  /usr/bin/python3 bench/bench_scaling.py BUILD/apps/cdyn [WORKDIR] [--n 40,80,160,320,640] [--steps 20]
            [--first K] [--resting] [--no-wellposed]
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys


def run(cdyn, n, steps, work, sets):
    out = os.path.join(work, f"n{n}_s{steps}" + "".join("_" + v.split("=")[0].split(".")[-1] for v in sets))
    args = ["/usr/bin/time", "-v", cdyn, "run", "--out", out, "--quiet", "--set", f"mesh.n={n}",
            "--set", f"time.T={steps * 0.001}", "--set", "output.fields=false",
            "--set", "output.plots=false", "--set", "output.every=1000000"]
    for v in sets:
        args += ["--set", v]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"cdyn run failed for n = {n}:\n{p.stderr[-3000:]}")
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1))
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([0-9:.]+)", p.stderr).group(1)
    parts = [float(x) for x in wall.split(":")]
    wall_s = sum(v * 60 ** (len(parts) - 1 - i) for i, v in enumerate(parts))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    with open(os.path.join(out, "history.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if int(r["step"]) > 0]
    contact = [float(r["solve_s"]) for r in rows if int(r["active"]) > 0]
    return s, rss, wall_s, contact, [float(r["step_s"]) for r in rows]


def fit(points):
    xs = [math.log(p[0]) for p in points]
    ys = [math.log(p[1]) for p in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cdyn")
    ap.add_argument("work", nargs="?", default="out/bench_scaling")
    ap.add_argument("--n", default="40,80,160,320,640")
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--first", type=int, default=0,
                    help="also the mean step over steps 1..FIRST of the same runs (history.csv's step_s), "
                         "and its exponent: both windows from one run per size")
    ap.add_argument("--resting", action="store_true", help="start on the obstacle (initial.u = 0)")
    ap.add_argument("--no-wellposed", action="store_true", help="skip condition (12) (output.wellposed = false)")
    a = ap.parse_args()
    sets = (["initial.u=0"] if a.resting else []) + (["output.wellposed=false"] if a.no_wellposed else [])
    os.makedirs(a.work, exist_ok=True)
    print(f"load average at start: {os.getloadavg()[0]:.2f}")
    print(f"| n | free dofs | steps | s/step | ns per dof and step | QP s/step | contact steps | QP s/step in contact | whole process (s) | peak RSS (MB) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    points, qpoints, cpoints, fpoints, steady = [], [], [], [], []
    for n in [int(v) for v in a.n.split(",")]:
        s, rss, wall, contact, step_s = run(a.cdyn, n, a.steps, a.work, sets)
        if a.first:
            fpoints.append((s["n_free"], sum(step_s[:a.first]) / len(step_s[:a.first])))
            print(f"  n = {n}: steps 1-{a.first} of the same run: {fpoints[-1][1] * 1e3:.2f} ms a step", flush=True)
        if len(step_s) > 1:  # steps 2.., without step 1's analysis and first factorization
            steady.append((n, s["n_free"], sum(step_s[1:]) / len(step_s[1:])))
        points.append((s["n_free"], s["s_per_step"]))
        qpoints.append((s["n_free"], s["qp_s_per_step"]))
        in_contact = "—"
        if contact:
            cpoints.append((s["n_free"], sum(contact) / len(contact)))
            in_contact = f"{cpoints[-1][1] * 1e3:.2f} ms"
        print(f"| {n} | {s['n_free']} | {s['n_steps']} | {s['s_per_step'] * 1e3:.2f} ms | {s['s_per_step'] / s['n_free'] * 1e9:.1f} | "
              f"{s['qp_s_per_step'] * 1e3:.2f} ms | {len(contact)} | {in_contact} | {wall:.1f} | {rss / 1024:.0f} |",
              flush=True)
    if len(points) >= 2:
        print(f"fitted exponent: time/step ~ N^{fit(points):.2f} (QP part N^{fit(qpoints):.2f}); target <= 1.1 from n = 160 to 640")
        local = [f"{fit(points[k:k + 2]):.2f}" for k in range(len(points) - 1)]
        print(f"local exponents between consecutive sizes: {', '.join(local)}")
    if len(steady) >= 2:
        print(f"steps 2-{a.steps} (history.csv's step_s, without step 1's analysis and factorization): " +
              ", ".join(f"n = {n} {t * 1e3:.2f} ms ({t / N * 1e9:.1f} ns per dof)" for n, N, t in steady))
        target = [(N, t) for n, N, t in steady if 160 <= n <= 640]
        if len(target) >= 2:
            local = [f"{fit(target[k:k + 2]):.2f}" for k in range(len(target) - 1)]
            print(f"steps 2-{a.steps}, n = 160 ... 640: N^{fit(target):.2f} (between consecutive sizes {', '.join(local)}); "
                  "target <= 1.1")
    if len(fpoints) >= 2:
        print(f"fitted exponent over steps 1-{a.first}: time/step ~ N^{fit(fpoints):.2f}")
    if len(cpoints) >= 2:
        print(f"fitted exponent of the QP time per contact step: N^{fit(cpoints):.2f}")
    print(f"load average at end: {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
