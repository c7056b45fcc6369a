#!/usr/bin/python3
"""bench_mpi.py — the PETSc back end on this machine's cores: strong scaling of the step
QP and what it exchanges (docs/distributed.md, "Measured").

Usage: bench_mpi.py CDYN MPIEXEC SOURCE_DIR OUT_DIR [--sizes 16,32] [--pcs gamg,jacobi] [--native factor,cg] [--log]
                     [--partitions none,graph]
       bench_mpi.py CDYN MPIEXEC SOURCE_DIR OUT_DIR --saddle P1+/P1,P2/P1 [--sizes 80]

The scene: data/scenes/cube_3d.toml, the unit cube falling onto a plane (as
bench_three_d.py: dt = h/2, 16 steps, contact from step 6 on), P1+/P0 midpoint with the
bubbles condensed.  For each size, one run of each of
  - native pdas (the Cholesky factor, CG while the active set moves) and the native
    CG path (solver.linear = "cg"), or only those --native names (scripts/bench.sh: cg,
    the path the PETSc pdas distributes; the factor's n = 32 run alone is 100 s and
    4.2 GB, and bench_three_d.py measures that path),
  - petsc pdas on 1 and on 2 ranks, for each preconditioner and each solver.partition
    of --partitions (none: rank 0 holds the whole problem; graph, slabs: each rank its
    cells, docs/distributed.md "Subdomains"),
reporting the mean over the contact window (steps 6–16) of history.csv's solve_s (the
step QP) and step_s (the whole step), the strong-scaling speed-up of the QP and of the
step on 2 ranks and the QP's efficiency, summary.json's setup_s (the mesh, the assembly,
the scheme's set-up), and the peak memory of each process (/usr/bin/time, the largest
rank).
One thread per process.  With --log, the last size's 2-rank run of the last
preconditioner runs with PETSc's -log_view (its events are counted in any run; the
option only prints them), whose summary gives the messages and reductions a step's QP
makes (the weak-scaling model's inputs): printed after the table.

With --saddle, the pairs whose step is in saddle form instead: the seed's membrane (the
embedded scene, 300 steps of dt = 0.001 through the impact at step 257), native pdas
(UMFPACK's LU) against petsc pdas (MUMPS's LDLᵀ) on 1 and 2 ranks, the mean over every
step.  Not in scripts/bench.sh (about 5 minutes at n = 80): docs/distributed.md's table.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

WINDOW = (6, 16)


def scene(n):
    h = 1.0 / n
    return [f"mesh.n={n}", f"obstacle.point=[0, 0, {-h / 2!r}]", f"time.dt={h / 2!r}", f"time.T={16 * h / 2!r}",
            "output.probes={}", "output.wellposed=false", "method.pair=P1+/P0", "time.scheme=midpoint"]


def membrane(n, pair):
    return [f"mesh.n={n}", f"method.pair={pair}", "time.T=0.3", "output.wellposed=false"]


def run(a, out, ranks, sets, extra_env=None):
    timed = ["/usr/bin/time", "-f", "peak_kB %M", a.cdyn, "run"] + ([a.scene] if a.scene else []) + [
        "--out", out, "--quiet", "--set", "output.fields=false", "--set", "output.plots=false"]
    args = ([a.mpiexec, "--oversubscribe", "-n", str(ranks)] if ranks else []) + timed
    for s in sets:
        args += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", **(extra_env or {}))
    p = subprocess.run(args, check=True, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    peak_kB = max(int(k) for k in re.findall(r"peak_kB (\d+)", p.stderr))
    with open(os.path.join(out, "history.csv")) as f:
        rows = [r for r in csv.DictReader(f) if a.saddle and int(r["step"]) > 0 or WINDOW[0] <= int(r["step"]) <= WINDOW[1]]
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    mean = lambda key: sum(float(r[key]) for r in rows) / len(rows)  # noqa: E731
    return mean("solve_s"), mean("step_s"), peak_kB, summary, p.stdout


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cdyn")
    ap.add_argument("mpiexec")
    ap.add_argument("source")
    ap.add_argument("out")
    ap.add_argument("--sizes", default=None, help="mesh sizes (default 16,32; with --saddle 80)")
    ap.add_argument("--pcs", default="gamg,jacobi")
    ap.add_argument("--native", default="factor,cg")
    ap.add_argument("--log", action="store_true")
    ap.add_argument("--partitions", default="none", help="solver.partition values of the petsc runs")
    ap.add_argument("--saddle", default="", help="pairs in saddle form, on the membrane (e.g. P1+/P1,P2/P1)")
    a = ap.parse_args()
    if a.saddle:
        return saddle_table(a, [int(s) for s in (a.sizes or "80").split(",")])
    a.scene = os.path.join(a.source, "data", "scenes", "cube_3d.toml")
    print("| n | unknowns | back end | ranks | set-up (s) | QP (s/step) | step (s/step) | QP speed-up | efficiency "
          "| step speed-up | peak memory per process (MB) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    sizes, pcs = [int(s) for s in (a.sizes or "16,32").split(",")], a.pcs.split(",")
    log = ""
    for n in sizes:
        base = scene(n)
        native = {"factor": ("native factor", []), "cg": ("native cg", ["solver.linear=cg"])}
        for label, sets in (native[k] for k in a.native.split(",") if k):
            qp, step, peak, summary, _ = run(a, os.path.join(a.out, f"n{n}_{label.replace(' ', '_')}"), 0, base + sets)
            print(f"| {n} | {summary['n_free']} | {label} | 1 | {summary['setup_s']:.3g} | {qp:.4g} | {step:.4g} | | | "
                  f"| {peak / 1024:.0f} |", flush=True)
        for partition in a.partitions.split(","):
            for pc in pcs:
                one = None
                for ranks in (1, 2):
                    sets = base + ["solver.backend=petsc", f"solver.pc={pc}", f"solver.partition={partition}"]
                    logged = a.log and ranks == 2 and n == sizes[-1] and pc == pcs[-1]
                    tag = f"n{n}_petsc_{pc}_{ranks}" + ("" if partition == "none" else "_" + partition)
                    qp, step, peak, summary, stdout = run(a, os.path.join(a.out, tag), ranks, sets,
                                                          {"PETSC_OPTIONS": "-log_view"} if logged else None)
                    if logged:
                        log = stdout
                    one = one or (qp, step)
                    speedup = f"{one[0] / qp:.2f} | {one[0] / qp / ranks:.2f} | {one[1] / step:.2f}" if ranks > 1 else " | | "
                    form = "" if partition == "none" else f", {partition}"
                    print(f"| {n} | {summary['n_free']} | petsc pdas {pc}{form} | {ranks} | {summary['setup_s']:.3g} "
                          f"| {qp:.4g} | {step:.4g} | {speedup} | {peak / 1024:.0f} |", flush=True)
    if a.log:
        keep = re.compile(r"^(Summary of Stages|Time \(sec\)|MPI Msg|MPI Reductions|MatMult |VecTDot|VecNorm|"
                          r"KSPSolve|PCSetUp|PCApply|MatZeroRowsCol|Event |Max |-----)")
        print("\nPETSc -log_view (2 ranks, n = %d, pc %s), the lines the model uses:" % (sizes[-1], pcs[-1]))
        for line in log.splitlines():
            if keep.match(line):
                print("    " + line)


def saddle_table(a, sizes):
    a.scene = ""
    print("| pair | n | unknowns X | back end | ranks | QP (s/step) | step (s/step) | QP speed-up | peak memory per process (MB) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for pair in a.saddle.split(","):
        for n in sizes:
            tag = f"{pair.replace('/', '').replace('+', 'b')}_n{n}"
            qp, step, peak, summary, _ = run(a, os.path.join(a.out, tag + "_native"), 0, membrane(n, pair))
            print(f"| {pair} | {n} | {summary['n_free']} | native (UMFPACK) | 1 | {qp:.4g} | {step:.4g} | | {peak / 1024:.0f} |",
                  flush=True)
            one = None
            for ranks in (1, 2):
                qp, step, peak, summary, _ = run(a, os.path.join(a.out, f"{tag}_petsc{ranks}"), ranks,
                                                 membrane(n, pair) + ["solver.backend=petsc"])
                one = one or qp
                print(f"| {pair} | {n} | {summary['n_free']} | petsc pdas (MUMPS) | {ranks} | {qp:.4g} | {step:.4g} | "
                      f"{one / qp:.2f} | {peak / 1024:.0f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
