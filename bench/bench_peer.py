#!/usr/bin/python3
"""bench_peer.py — cdyn against the peer a user would pick instead (docs/performance.md (b)).

The seed's dynamic membrane (data/scenes/membrane.toml: f = −0.6, u = 0.02 on the
boundary and at t = 0, u ≥ 0 at the vertices, dt = 0.001) with P1/P1 and backward Euler,
on FreeFEM's square(n, n), integrated
  - by FreeFEM + ff-Ipopt, one Ipopt solve per step (reference_scripts/bench_peer_membrane.edp:
    bound_relax_factor = 0, tol = 1e-13, mu_min = 1e-20), and
  - by `cdyn run` with the pdas step solver at solver.tol = 1e-12, twice: method.pair = P1/P1
    (M = Bᵀ C⁻¹ B in saddle form, UMFPACK) and method.mass = consistent (the same M
    assembled explicitly, CHOLMOD),
for n = 40, 80, 160.  Checks that the energies agree at every step to 1e-6 relative to
J0 (the tolerance of tests/reference/compare_dynamic.py) and prints the mean time per
step of each over the window --first … --steps and the ratio FreeFEM / cdyn (target
≥ 100).  The window is the contact: by default steps 241-300, the impact at step ~257
and the 43 steps in contact after it.  FreeFEM solves the free-flight steps before the
window as linear systems (checking u ≥ 0 at each: the bound is then inactive and the
step's QP has that solution) and times its window's loop with clock(); cdyn runs every
step as always, and its time is the mean of history.csv's step_s over the window plus
what its loop spends per step outside the scheme's step (energy, history: s_per_step
minus the run's mean step_s).  Both single-threaded, so the two agree up to the load
of the machine.

With --resting both start on the obstacle (u(0) = 0 inside, 0.02 on the boundary):
resting contact, most vertices active, lifting off slowly (docs/performance.md, "Contact
in every regime").

Usage:  /usr/bin/python3 bench/bench_peer.py BUILD/apps/cdyn [WORKDIR] [--n 40,80,160] [--steps 300] [--first 241] [--resting]
Exit status 1 if an energy differs by more than 1e-6 relative.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
EDP = os.path.join(HERE, "..", "reference_scripts", "bench_peer_membrane.edp")
TOL = 1e-6


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run_freefem(n, steps, first, work, u0):
    out = os.path.join(work, f"freefem_n{n}_u{u0}.csv")
    env = dict(os.environ, FF_LOADPATH="/usr/lib/freefem++")
    t = time.time()
    p = subprocess.run(["FreeFem++", "-nw", "-v", "0", EDP, "-pair", "P1", "-scheme", "backward_euler", "-n", str(n),
                        "-dt", "0.001", "-steps", str(steps), "-first", str(first), "-u0", str(u0), "-out", out], env=env,
                       capture_output=True, text=True)
    wall = time.time() - t
    m = re.search(r"timing: steps (\d+) loop_s ([0-9.eE+-]+) ipopt_s ([0-9.eE+-]+)", p.stdout)
    if p.returncode != 0 or not m:
        sys.exit(f"FreeFEM failed (n = {n}):\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
    window = int(m.group(1))
    return read_csv(out), float(m.group(2)) / window, float(m.group(3)) / window, wall


def run_cdyn(cdyn, n, steps, work, method, u0):
    out = os.path.join(work, f"cdyn_n{n}_u{u0}_{method.replace('/', '').replace('=', '_')}")
    subprocess.run([cdyn, "run", "--out", out, "--quiet", "--set", f"mesh.n={n}", "--set", method,
                    "--set", f"initial.u={u0!r}",
                    "--set", "time.scheme=backward_euler", "--set", "time.dt=0.001", "--set", f"time.T={steps * 0.001}",
                    "--set", "solver.tol=1e-12", "--set", "output.fields=false", "--set", "output.plots=false"],
                   check=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return read_csv(os.path.join(out, "history.csv")), summary


def window_seconds(history, summary, first):
    """cdyn's mean time per step over steps first …: the scheme's step (history.csv's step_s)
    plus the loop's per-step remainder (energy, history row), s_per_step minus the mean step_s."""
    step_s = [float(r["step_s"]) for r in history[1:]]
    rest = summary["s_per_step"] - sum(step_s) / len(step_s)
    window = step_s[first - 1:]
    return sum(window) / len(window) + rest


def energy_difference(ff, cd):
    J0 = abs(float(ff[0]["E_total"]))
    return max(abs(float(a["E_total"]) - float(b["E_total"])) / J0 for a, b in zip(ff, cd))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cdyn")
    ap.add_argument("work", nargs="?", default="out/bench_peer")
    ap.add_argument("--n", default="40,80,160")
    ap.add_argument("--steps", type=int, default=300, help="steps (the impact is at step ~257)")
    ap.add_argument("--first", type=int, default=None,
                    help="the window's first step (default 241; 1 with --resting): FreeFEM solves the steps before "
                         "it without the bound, checking they stay above it")
    ap.add_argument("--resting", action="store_true",
                    help="start on the obstacle (u(0) = 0 inside, 0.02 on the boundary): resting contact, most "
                         "vertices active, slow lift-off")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    print(f"load average at start: {os.getloadavg()[0]:.2f}")
    first = a.first if a.first is not None else (1 if a.resting else 241)
    if not 1 <= first <= a.steps:
        ap.error(f"--first {first}: the window must start at a step in 1 … --steps ({a.steps})")
    print(f"window: steps {first}-{a.steps}")
    print("| n | unknowns | window | contact steps | FreeFEM+Ipopt s/step (Ipopt part) | cdyn P1/P1 s/step | "
          "cdyn consistent s/step | ratio FreeFEM/cdyn (P1/P1, consistent) | max |dJ|/J0 |")
    print("|---|---|---|---|---|---|---|---|---|")
    ok = True
    for n in [int(v) for v in a.n.split(",")]:
        u0 = 0.0 if a.resting else 0.02
        ff, ff_step, ff_ipopt, _ = run_freefem(n, a.steps, first, a.work, u0)
        cd, s1 = run_cdyn(a.cdyn, n, a.steps, a.work, "method.pair=P1/P1", u0)
        cc, s2 = run_cdyn(a.cdyn, n, a.steps, a.work, "method.mass=consistent", u0)
        if len(ff) != len(cd) or len(ff) != len(cc):
            sys.exit(f"n = {n}: {len(ff)} FreeFEM rows against {len(cd)}, {len(cc)} cdyn rows")
        dJ = max(energy_difference(ff, cd), energy_difference(ff, cc))
        ok = ok and dJ <= TOL
        contact = sum(1 for r in cd if int(r["active"]) > 0)
        t1, t2 = window_seconds(cd, s1, first), window_seconds(cc, s2, first)
        print(f"| {n} | {s1['n_free']} | {first}-{a.steps} | {contact} | {ff_step * 1e3:.1f} ms ({ff_ipopt * 1e3:.1f} ms) | "
              f"{t1 * 1e3:.2f} ms | {t2 * 1e3:.2f} ms | "
              f"{ff_step / t1:.0f}x, {ff_step / t2:.0f}x | {dJ:.1e} |", flush=True)
    print(f"load average at end: {os.getloadavg()[0]:.2f}")
    if not ok:
        print(f"FAIL: an energy differs by more than {TOL} relative to J0")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
