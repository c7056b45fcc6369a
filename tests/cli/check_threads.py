#!/usr/bin/env python3
"""check_threads.py — the thread count of a run (docs/scenes.md, `solver.threads`;
docs/performance.md, "Both cores").

Usage: check_threads.py CDYN SOURCE_DIR WORKDIR

 1. The seed's membrane at n = 80 through its impact (T = 0.3: 300 steps, the impact at
    step ≈ 258), P1+/P0 midpoint and P1/P1 backward Euler — large enough for the
    kernel's loops to run in parallel — with solver.threads = 1 and = 2: history.csv's
    rows equal, every column but the timings `solve_s`, `step_s`, `reconstruction_s` as text (17 digits:
    bit for bit); summary.json's `threads` is the key's value, and `blas_threads` (the
    BLAS's own count, which the key leaves alone) the same in both.
 2. Without the key the count is the environment's: OMP_NUM_THREADS = 1 and = 2 give
    `threads` 1 and 2, and OpenBLAS follows OMP_NUM_THREADS when OPENBLAS_NUM_THREADS is
    not set (`blas_threads` null with another BLAS); the key overrides OMP_NUM_THREADS;
    the printed paragraph names the count.
 3. More threads than cores: run, with a warning naming the key.
Only the standard library is used.
"""
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import QUIET, check, failures  # noqa: E402

cdyn, src, work = sys.argv[1:4]
TIMING = {"solve_s", "step_s", "reconstruction_s"}
METHODS = {"P1+/P0 midpoint": ["method.pair=P1+/P0", "time.scheme=midpoint"],
           "P1/P1 backward_euler": ["method.pair=P1/P1", "time.scheme=backward_euler"]}
IMPACT = ["mesh.n=80", "time.T=0.3"]


def run(name, sets, env=None, quiet=True, unset=()):
    """`cdyn run` of the default scene (the seed's membrane), with `env` added to the
    environment and the variables `unset` removed → (summary, history lines, stdout)."""
    out = os.path.join(work, name)
    shutil.rmtree(out, ignore_errors=True)
    args = [cdyn, "run", "--out", out] + (QUIET if quiet else ["--set", "output.fields=false",
                                                               "--set", "output.plots=false"])
    for s in sets:
        args += ["--set", s]
    environment = {k: v for k, v in os.environ.items() if k not in unset}
    done = subprocess.run(args, check=True, stdout=subprocess.PIPE, text=True, env=dict(environment, **(env or {})))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "history.csv")) as f:
        history = f.read().splitlines()
    return summary, history, done.stdout


def without_timings(history):
    """The history's rows with the timing columns dropped, as text."""
    header = history[0].split(",")
    keep = [k for k, name in enumerate(header) if name not in TIMING]
    return [[row.split(",")[k] for k in keep] for row in history]


# 1. one thread against two, bit for bit
for method, sets in METHODS.items():
    tag = method.split()[0].replace("/", "_").replace("+", "p")
    runs = {}
    for threads in (1, 2):
        runs[threads] = run(f"impact_{tag}_{threads}", IMPACT + sets + [f"solver.threads={threads}"])
        summary = runs[threads][0]
        check(summary["threads"] == threads, f"{method}: solver.threads = {threads} runs on {summary['threads']}")
    check(runs[1][0]["blas_threads"] == runs[2][0]["blas_threads"],
          f"{method}: the BLAS's count is not the key's ({runs[1][0]['blas_threads']} and {runs[2][0]['blas_threads']})")
    one, two = without_timings(runs[1][1]), without_timings(runs[2][1])
    check(runs[1][0]["max_active"] > 0, f"{method}: the run has contact (max_active {runs[1][0]['max_active']})")
    check(len(one) == 302 and len(one) == len(two), f"{method}: 300 steps in both histories (and step 0)")
    differing = [k for k, (a, b) in enumerate(zip(one, two)) if a != b]
    check(not differing, f"{method}: history.csv on 1 and 2 threads equal bit for bit"
          + (f" (first difference at row {differing[0]})" if differing else ""))
    for key in ("E0", "E_final", "E_rel_drift", "max_violation", "qp_iters_mean", "kkt_residual_max"):
        check(runs[1][0][key] == runs[2][0][key], f"{method}: summary.json {key} equal on 1 and 2 threads")

# 2. the environment's count, the key over it, the printed paragraph
SHORT = ["time.T=0.002"]
for threads in (1, 2):
    summary, _, _ = run(f"environment_{threads}", SHORT, env={"OMP_NUM_THREADS": str(threads)},
                        unset=["OPENBLAS_NUM_THREADS"])
    check(summary["threads"] == threads and summary["blas_threads"] in (None, threads),
          f"OMP_NUM_THREADS={threads}: threads = {summary['threads']}, blas_threads = {summary['blas_threads']}")
summary, _, _ = run("key_over_environment", SHORT + ["solver.threads=2"], env={"OMP_NUM_THREADS": "1"})
check(summary["threads"] == 2, f"solver.threads = 2 over OMP_NUM_THREADS=1: threads = {summary['threads']}")
_, _, printed = run("printed", SHORT + ["solver.threads=2"], quiet=False)
check(re.search(r"to T = [0-9.e-]+ in [0-9.]+ s on 2 threads \(", printed) is not None,
      "the run's paragraph says 'on 2 threads'")
_, _, printed = run("printed_one", SHORT + ["solver.threads=1"], quiet=False)
check(re.search(r" s on 1 thread \(", printed) is not None, "the run's paragraph says 'on 1 thread'")

# 3. more threads than cores: a warning, the same run
cores = os.cpu_count() or 1
summary, _, _ = run("more_than_cores", SHORT + [f"solver.threads={cores + 1}"])
check(summary["threads"] == cores + 1 and any("solver.threads" in w for w in summary["warnings"]),
      f"solver.threads = {cores + 1} on {cores} cores: run, with a warning naming the key")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
