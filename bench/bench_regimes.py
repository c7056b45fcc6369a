#!/usr/bin/python3
"""bench_regimes.py — the cost of contact in every regime (docs/performance.md, "Contact
in every regime"): the mean wall time of a step over a window of steps with the
obstacle, against the same steps without it (obstacle.enabled = false: the same S, one
forward/back solve per step), for P1+/P0 midpoint and P1/P1 backward Euler.

Usage: bench_regimes.py CDYN SOURCE_DIR OUT_DIR [--repeat R] [--only NAME,...] [--cpu K]

Regimes (each a scene and a window of steps):
  impact    the seed's membrane, n = 160, dt = 0.001, steps 211–310: the impact and the
            chattering that follows (docs/performance.md (a))
  resting   the membrane started on the obstacle (initial.u = 0), n = 160, dt = 0.001,
            steps 1–100: most unknowns active, slow lift-off near the boundary
  chatter   the resting membrane under a load that lifts it off and presses it back,
            f = −0.6 + 3 sin(60 t): the active set sweeps in and out, steps 1–100
  disk      the elastic disk of data/scenes/disk.toml, the steps of its impact
  beam      the thin beam of data/scenes/beam.toml, the steps of its impact
Each (regime, method) runs R times with and R times without the obstacle, alternated,
so that both see the same machine; the figure is the ratio of the means over the window
of history.csv's step_s (the whole step: QP, update, reconstruction), averaged over the
repetitions — the mean, not the median: the slow steps are the point.  Beside it, the
lowest and highest ratio of one repetition's pair (its contact run over the linear run
next to it): how far the machine moved the figure while the table was made.  Then the
same means of the step QP's part (solve_s) and of the full-step reconstruction's
(reconstruction_s, the midpoint rule's eq. 14 for P1+/P0), contact / linear: where the
overhead is.  One core (OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1), fields and plots
off, every run on the same CPU (--cpu, by default the first this process may use): the
cores of a virtual machine need not be equally fast (docs/performance.md, "Both cores":
the second core of the 2-core machine ran the linear impact window 1.2–2.2 times slower
than the first), and a contact run on one with its linear run on the other gave ratios
of 0.8 to 1.7.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

METHODS = {
    "P1+/P0 midpoint": ["method.pair=P1+/P0", "time.scheme=midpoint"],
    "P1/P1 backward_euler": ["method.pair=P1/P1", "time.scheme=backward_euler"],
}
MEMBRANE = ["mesh.n=160", "time.dt=0.001"]
REGIMES = {
    "impact": (None, MEMBRANE + ["time.T=0.31"], (211, 310)),
    "resting": (None, MEMBRANE + ["initial.u=0", "time.T=0.1"], (1, 100)),
    "chatter": (None, MEMBRANE + ["initial.u=0", "time.T=0.1", "physics.f=-0.6 + 3 * sin(60 * t)"], (1, 100)),
    "disk": ("disk.toml", [], "contact"),
    "beam": ("beam.toml", [], "contact"),
}


def run(cdyn, scene, out, sets):
    args = [cdyn, "run"] + ([scene] if scene else []) + ["--out", out, "--quiet",
                                                       "--set", "output.fields=false", "--set", "output.plots=false"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, env=dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1"))
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        return rows, json.load(f)


def window_of(rows, window):
    """The steps of the window: given, or those with an active constraint and the next."""
    if window != "contact":
        return window
    steps = [int(r["step"]) for r in rows if float(r["active"]) > 0]
    return (min(steps), max(steps) + 1)


def mean_step(rows, window, column="step_s"):
    """The mean of a column over the window (0 for a column the run does not write)."""
    a, b = window
    times = [float(r.get(column, 0.0)) for r in rows if a <= int(r["step"]) <= b]
    return sum(times) / len(times)


def parts(rows, window):
    """The step's mean and two of its parts: the step QP (solve_s) and the full-step
    reconstruction (reconstruction_s, P1+/P0 midpoint's eq. 14)."""
    return [mean_step(rows, window, c) for c in ("step_s", "solve_s", "reconstruction_s")]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cdyn")
    ap.add_argument("src")
    ap.add_argument("out")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="")
    ap.add_argument("--cpu", type=int, default=min(os.sched_getaffinity(0)))
    a = ap.parse_args()
    os.sched_setaffinity(0, {a.cpu})  # (the runs inherit it)
    only = set(a.only.split(",")) if a.only else set(REGIMES)
    os.makedirs(a.out, exist_ok=True)
    table = []
    print(f"{'regime':9} {'method':22} {'window':>9} {'contact ms':>10} {'linear ms':>9} {'ratio':>6} "
          f"{'pairs':>9} {'max active':>10} {'unknowns':>8} {'QP ms c/l':>13} {'rec. ms c/l':>13}  "
          f"(mean over the window, {a.repeat} repetitions, CPU {a.cpu})")
    for name, (scene_file, sets, window) in REGIMES.items():
        if name not in only:
            continue
        scene = os.path.join(a.src, "data", "scenes", scene_file) if scene_file else None
        for method, msets in METHODS.items():
            contact, linear, active, unknowns = [], [], 0, 0
            for k in range(a.repeat):
                out = os.path.join(a.out, f"{name}_{method.split()[0].replace('/', '_')}")
                rows, s = run(a.cdyn, scene, out + "_contact", sets + msets)
                w = window_of(rows, window)
                contact.append(parts(rows, w))
                active = max(active, s["max_active"])
                unknowns = s["n_free"]
                rows, _ = run(a.cdyn, scene, out + "_linear", sets + msets + ["obstacle.enabled=false"])
                linear.append(parts(rows, w))
            # (step, QP, reconstruction) in ms, each the mean over the repetitions
            (c, cq, cr), (l, lq, lr) = [[1e3 * sum(p[j] for p in runs) / len(runs) for j in range(3)]
                                        for runs in (contact, linear)]
            pairs = [cp[0] / lp[0] for cp, lp in zip(contact, linear)]  # (each repetition's step means)
            table.append({"regime": name, "method": method, "window": list(w), "contact_ms": c, "linear_ms": l,
                          "ratio": c / l, "pair_ratios": pairs, "max_active": active, "unknowns": unknowns, "contact_qp_ms": cq,
                          "linear_qp_ms": lq, "contact_reconstruction_ms": cr, "linear_reconstruction_ms": lr})
            print(f"{name:9} {method:22} {w[0]:>4}-{w[1]:<4} {c:10.3f} {l:9.3f} {c / l:6.2f} "
                  f"{min(pairs):4.2f}-{max(pairs):4.2f} {active:10d} {unknowns:8d} {cq:6.3f}/{lq:6.3f} {cr:6.3f}/{lr:6.3f}", flush=True)
    with open(os.path.join(a.out, "regimes.json"), "w") as f:
        json.dump(table, f, indent=1)
    worst = max(r["ratio"] for r in table)
    print(f"worst ratio {worst:.2f} (target <= 1.5)")


if __name__ == "__main__":
    sys.exit(main())
