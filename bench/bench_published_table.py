#!/usr/bin/python3
"""bench_published_table.py — the seed author's published table (docs/references.md,
REFERENCES: relative energy error at T of the membrane, P1+/P0 and P2/P1, N_X = 10, 20,
40, dt = 0.01 … 0.0004, midpoint, T = 0.8) re-run with cdyn, for the three ways of
treating the full steps (docs/schemes.md):

  - midpoint with U^{n+1} = 2U^{n+½} − Uⁿ as it comes (the seed's algorithm),
  - midpoint with physical full steps (eq. 14: by the local basis of Ker B for P1+/P0,
    by multipliers for P2/P1),
  - discrete_gradient.

For each cell: |J(T) − J0|/J0, max_t |J − J0|/J0, the largest violation at the full steps
and the wall time per step of the three; the discrete gradient's time against the
reconstructed midpoint's, by the mean per step over interleaved repetitions of the two
runs: as many as fit in about 0.4 s of the discrete gradient's runs, at most 5 (a run of
80 steps of 0.1–2 ms moves by ±0.1 in the ratio; the long runs of the small steps are
their own window).  One core (OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1).

    /usr/bin/python3 bench/bench_published_table.py build/apps/cdyn out/published
"""
import json
import os
import subprocess
import sys

PUBLISHED = {  # the seed author's |J(T) − J0|/J0 in %
    ("P1+/P0", 10): [7.50, 3.06, 0.493, 0.0267], ("P1+/P0", 20): [27.7, 3.25, 0.348, 0.060],
    ("P1+/P0", 40): [96.9, 22.8, 0.856, 0.242], ("P2/P1", 10): [0.687, 0.027, 0.040, 8.3e-4],
    ("P2/P1", 20): [1.29, 0.41, 0.0125, 0.0042]}
DTS = [0.01, 0.004, 0.001, 0.0004]


def run(cdyn, out, pair, n, dt, scheme, reconstruct):
    name = f"{pair.replace('/', '_').replace('+', 'b')}_n{n}_dt{dt}_{scheme}_{'r' if reconstruct else 'x'}"
    d = os.path.join(out, name)
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    subprocess.run([cdyn, "run", "--out", d, "--quiet", "--set", f"method.pair={pair}", "--set", f"mesh.n={n}",
                    "--set", f"time.dt={dt}", "--set", f"time.scheme={scheme}", "--set",
                    f"time.reconstruct={'true' if reconstruct else 'false'}", "--set", "output.fields=false",
                    "--set", "output.plots=false"], check=True, env=env)
    with open(os.path.join(d, "summary.json")) as f:
        s = json.load(f)
    return s


def main():
    cdyn, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    print("| pair | N_X | dt | published % | extrapolated: J(T) %, max_t %, violation | reconstructed: J(T) %, max_t %, "
          "violation | discrete_gradient: J(T) %, max_t %, violation | s/step: extrapolated, reconstructed, DG "
          "(DG/reconstructed, by the mean over the runs) |")
    print("|---|---|---|---|---|---|---|---|")
    worst_dg, worst_ratio = 0.0, 0.0
    for (pair, n), published in PUBLISHED.items():
        for dt, pub in zip(DTS, published):
            cells = []
            x = run(cdyn, out, pair, n, dt, "midpoint", False)
            cells.append(x)
            r = run(cdyn, out, pair, n, dt, "midpoint", True)
            g = run(cdyn, out, pair, n, dt, "discrete_gradient", True)
            reps = max(1, min(5, int(0.4 / max(g["wall_s"], 1e-3))))
            r_times, g_times = [r["s_per_step"]], [g["s_per_step"]]
            for _ in range(reps - 1):
                r_times.append(run(cdyn, out, pair, n, dt, "midpoint", True)["s_per_step"])
                g_times.append(run(cdyn, out, pair, n, dt, "discrete_gradient", True)["s_per_step"])
            r_mean, g_mean = sum(r_times) / reps, sum(g_times) / reps

            def fmt(s):
                err = abs(s["E_final"] - s["E0"]) / abs(s["E0"]) * 100
                return f"{err:.3g}, {s['E_rel_drift'] * 100:.3g}, {s['max_violation']:.1e}"
            ratio = g_mean / r_mean
            worst_dg = max(worst_dg, g["E_rel_drift"])
            worst_ratio = max(worst_ratio, ratio)
            cost = (f"{x['s_per_step'] * 1e3:.3f}, {r_mean * 1e3:.3f}, {g_mean * 1e3:.3f} ms "
                    f"({ratio:.2f}, {reps} run{'s' if reps > 1 else ''})")
            print(f"| {pair} | {n} | {dt} | {pub} | {fmt(x)} | {fmt(r)} | {fmt(g)} | {cost} |")
    print(f"\ndiscrete_gradient: max over the cells of max_t |J - J0|/J0 = {worst_dg:.2e}; "
          f"largest time ratio DG/midpoint = {worst_ratio:.2f}")


if __name__ == "__main__":
    main()
