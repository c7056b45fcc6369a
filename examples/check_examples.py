#!/usr/bin/env python3
"""check_examples.py — runs one tutorial program and checks the figures it prints
against numbers the rest of the suite establishes (CTest label `examples`).

    check_examples.py N EXAMPLE CDYN SOURCE_DIR WORK_DIR

N is the example number, EXAMPLE its executable, CDYN the `cdyn` command line (built
from the same kernel: where an example and `cdyn run` make the same kernel calls they
must print the same numbers), SOURCE_DIR the repository, WORK_DIR a scratch folder.
Each check says where its reference number comes from and why its tolerance.
Exit status 0: all checks pass; 1: a check failed (one line per failure).
"""
import csv
import filecmp
import json
import math
import os
import re
import shutil
import subprocess
import sys

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def close(a, b, rel, what):
    check(abs(a - b) <= rel * abs(b), f"{what}: {a:.12g} vs {b:.12g} (relative tolerance {rel:g})")


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed with status {p.returncode}:\n{p.stdout}\n{p.stderr}")
    return p.stdout


def cdyn_run(cdyn, out, scene=None, sets=()):
    cmd = [cdyn, "run"] + ([scene] if scene else [])
    for s in ("output.plots=false",) + tuple(sets):
        cmd += ["--set", s]
    run(cmd + ["--out", out, "--quiet"])
    with open(os.path.join(out, "history.csv")) as f:
        history = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return history, summary


def check_energy_trace(text, history, expected_rows, tol):
    """Checks the rows `step t E_kin E_pot J active` an example prints against
    history.csv: expected_rows of them, E_kin, E_pot and J within tol·J0, the same
    active counts."""
    J0 = float(history[0]["E_total"])
    rows, worst, active = 0, 0.0, []
    for line in text.splitlines():
        f = line.split()
        if len(f) == 6 and f[0].isdigit():
            h = history[int(f[0])]
            for col, name in ((2, "E_kin"), (3, "E_pot"), (4, "E_total")):
                worst = max(worst, abs(float(f[col]) - float(h[name])) / abs(J0))
            if int(f[5]) != int(h["active"]):
                active.append(int(f[0]))
            rows += 1
    check(rows == expected_rows and worst <= tol and not active,
          f"energy trace: {rows} rows ({expected_rows} expected) as `cdyn run` history.csv to {tol:g} J0 "
          f"(largest difference {worst:.1e}; active differs at steps {active})")


# Where an example and `cdyn run` make the same kernel calls in the same order, the
# numbers are equal to the last bit (measured); 1e-13 relative leaves room for the
# compiler contracting a product differently in the two programs, and is 100 times
# below the scheme's own round-off drift (docs/schemes.md, midpoint: 1e-11 over 800 steps).
SAME_CALLS = 1e-13


def example1(exe, cdyn, src, work):
    text = run([exe])
    rows = {}  # (n, pair) -> fields
    n = None
    for line in text.splitlines():
        m = re.match(r"unit square n = (\d+):", line)
        if m:
            n = int(m.group(1))
            continue
        f = line.split()
        if len(f) == 7 and "/" in f[0]:
            rows[(n, f[0])] = f
    check(len(rows) == 15, f"15 rows printed (3 meshes x 5 pairs), got {len(rows)}")
    for n in (4, 6, 10):
        ref = json.loads(run([cdyn, "wellposed", "--set", f"mesh.n={n}", "--json"]))
        for r in ref:
            key = (n, r["pair"])
            if key not in rows:
                continue
            f = rows[key]
            check([int(x) for x in f[1:5]] == [r["N_W"], r["N_H"], r["dim_ker_B"], r["N_g"]],
                  f"n={n} {r['pair']}: N_W, N_H, dim Ker B, N_g as `cdyn wellposed`")
            # β printed with 11 significant digits: equal to that rounding.
            check(abs(float(f[5]) - r["beta"]) <= 1e-10 * max(r["beta"], 1e-300) or float(f[5]) == r["beta"],
                  f"n={n} {r['pair']}: beta {f[5]} as `cdyn wellposed` ({r['beta']:.10e})")
            check((f[6] == "yes") == r["satisfied"], f"n={n} {r['pair']}: condition (12) decision as `cdyn wellposed`")
        # dim Ker B < N_g forces β = 0 exactly (tests/unit/test_wellposedness.cpp, SeedMembraneTable).
        for pair in ("P1/P1", "P1/P0"):
            check(float(rows[(n, pair)][5]) == 0.0 and rows[(n, pair)][6] == "no", f"n={n} {pair}: beta = 0, (12) fails")
    # tests/cli/CMakeLists.txt (cli_wellposed): P1+/P0 at h = 0.1 has β = 3.0900e-01.
    check(rows[(10, "P1+/P0")][5].startswith("3.0900"), "n=10 P1+/P0: beta 3.0900e-01 (cli_wellposed)")


def example2(exe, cdyn, src, work):
    text = run([exe])
    history, summary = cdyn_run(cdyn, os.path.join(work, "run"), sets=("mesh.n=10", "output.fields=false"))
    check_energy_trace(text, history, 21, SAME_CALLS)  # every 40 steps of 800
    m = re.search(r"\|J\(T\) - J0\|/\|J0\| = (\S+), max over t of \|J - J0\|/\|J0\| = (\S+)", text)
    check(m is not None, "the energy balance line")
    close(float(m.group(2)), summary["E_rel_drift"], 1e-3, "max drift as summary.json E_rel_drift (4 printed digits)")
    # docs/experiments.md, first table, P1+/P0 at h = 0.1 with reconstructed full steps:
    # 2.72e-04 and 3.27e-04 (3 digits).
    close(float(m.group(1)), 2.72e-04, 2e-3, "|J(T) - J0|/J0 as docs/experiments.md")
    close(float(m.group(2)), 3.27e-04, 5e-3, "max |J - J0|/J0 as docs/experiments.md")


def example3(exe, cdyn, src, work):
    text = run([exe])
    table = {}
    for line in text.splitlines():
        f = line.split()
        if len(f) == 4 and f[0] in ("consistent", "lumped", "redistributed", "P1+/P0"):
            table[f[0]] = [float(x) for x in f[1:]]
    check(len(table) == 4, "four rows")
    # docs/bar_impact.md §6.1 (printed by tests/unit/test_bar_exact.cpp, BarConvergence),
    # clamped bar, n = 40, dt = 0.0125, midpoint: 4 printed digits.
    docs = {"P1+/P0": (8.799e-03, 1.901e-02, 3.774e-04), "redistributed": (1.023e-02, 1.956e-02, 3.270e-04)}
    for label, ref in docs.items():
        for name, a, b in zip(("L2(T)", "contact", "energy"), table[label], ref):
            close(a, b, 1e-3, f"{label} {name} as docs/bar_impact.md 6.1")
    # `cdyn run` on the bar scene with each mass (the scene's pair line replaced), the
    # step solver at the same tolerance: error_exact is the same ‖u_h(T) − u(T)‖_L2 and
    # E_rel_drift the same max |J − J0|/J0 (5 printed digits).
    with open(os.path.join(src, "data", "scenes", "bar.toml")) as f:
        bar = f.read()
    for label in table:
        method = 'pair = "P1+/P0"' if label == "P1+/P0" else f'mass = "{label}"'
        scene = os.path.join(work, f"bar_{label.replace('/', '_').replace('+', 'b')}.toml")
        with open(scene, "w") as f:
            f.write(re.sub(r'(?m)^pair = .*$', method, bar))
        _, s = cdyn_run(cdyn, scene[:-5], scene, ("time.T=3", "solver.tol=1e-13", "output.fields=false"))
        close(table[label][0], s["error_exact"], 1e-4, f"{label} L2(T) as `cdyn run` error_exact")
        close(table[label][2], s["E_rel_drift"], 1e-4, f"{label} energy as `cdyn run` E_rel_drift")
    # The inertial contact vertex: the energy is not controlled (> 0.5 J0, the bound of
    # BarConvergence.MidpointStandardMassLosesEnergyControl, asserted there for P1/P1).
    for label in ("consistent", "lumped"):
        check(table[label][2] > 0.5, f"{label}: energy error above 0.5 J0")


def example4(exe, cdyn, src, work):
    text = run([exe])
    dU = float(re.search(r"max_n \|U_jacobi - U_pdas\|_inf = (\S+)", text).group(1))
    dJ = float(re.search(r"max_n \|J_jacobi - J_pdas\|/J0 = (\S+)", text).group(1))
    # Both solvers stop at the same KKT tolerance 1e-12 (relative to |X| ~ 0.02); the
    # midpoint scheme carries a step's error forward undamped, so the difference may
    # grow with the 800 steps: measured 2.3e-12 in U, 2.3e-11 in J.  1e-9 is 400x above
    # that and 6 decades below what a different discrete solution gives (P1+/P0 against
    # P1/P1 on this problem differ by O(1) in J, docs/experiments.md).
    check(dU <= 1e-9, f"Jacobi and pdas give the same U to 1e-9 (max difference {dU:.3e})")
    check(dJ <= 1e-9, f"Jacobi and pdas give the same J to 1e-9 J0 (max difference {dJ:.3e})")
    J = float(re.search(r"Jacobi: \|J\(T\) - J0\|/J0 = (\S+)", text).group(1))
    close(J, 2.72e-04, 2e-3, "Jacobi run |J(T) - J0|/J0 as docs/experiments.md (P1+/P0, h = 0.1)")


def example5(exe, cdyn, src, work):
    geo = os.path.join(src, "data", "geo", "lshape.geo")
    mine = os.path.join(work, "example")
    shutil.rmtree(mine, ignore_errors=True)
    text = run([exe, geo, mine])
    # data/geo/lshape.geo: area 0.75.
    check(re.search(r"area 0\.750000,", text) is not None, "L-shape area 0.750000")
    ref = os.path.join(work, "run")
    history, _ = cdyn_run(cdyn, ref, os.path.join(src, "data", "scenes", "lshape.toml"))
    J0 = float(history[0]["E_total"])
    compared = 0
    for line in text.splitlines():
        f = line.split()
        if len(f) == 4 and f[0].isdigit():
            h = history[int(f[0])]
            check(abs(float(f[2]) - float(h["E_total"])) <= SAME_CALLS * J0 and int(f[3]) == int(h["active"]),
                  f"step {f[0]}: J and active as `cdyn run data/scenes/lshape.toml`")
            compared += 1
    check(compared == 10, "ten energy rows")
    # The same writer on the same states: the same bytes.
    with open(os.path.join(ref, "fields.pvd")) as a, open(os.path.join(mine, "fields.pvd")) as b:
        check(a.read() == b.read(), "fields.pvd identical to the one of `cdyn run`")
    vtus = sorted(os.listdir(os.path.join(ref, "fields")))
    check(len(vtus) == 51 and vtus == sorted(os.listdir(os.path.join(mine, "fields"))), "51 VTU files, same names")
    same = all(filecmp.cmp(os.path.join(ref, "fields", v), os.path.join(mine, "fields", v), shallow=False) for v in vtus)
    check(same, "every VTU file identical to the one of `cdyn run`")


# Example 6 steps the seed's membrane by hand and `cdyn run` through the kernel's scheme:
# the same QPs at the same KKT tolerance 1e-12, but cdyn condenses the bubbles out and
# PDAS may solve the condensed systems by CG, and r is formed by another route, so the
# two agree to the solver's tolerance, not to the bit.  Measured over all 800 steps
# (every step printed, against history.csv): max |J_ex6 - J_cdyn|/J0 = 8.5e-11 (step
# 277, in the first impact; 6.5e-13 before it, 2e-12 between impacts), E_kin 6.5e-12,
# E_pot 8.8e-11; the active counts equal at every step.  1e-9 is 12x above that, the
# bound example 4 puts on two solvers at one tolerance, and 7 decades below the 1.2e-2
# the impacts move J.  (With the solver's default tolerance 1e-10 in ex6 the difference
# measured 7.6e-9: the program must use the scene's 1e-12.)
BY_HAND = 1e-9


def example6(exe, cdyn, src, work):
    text = run([exe])
    # The program writes the midpoint step out with U^{n+1} = 2U^{n+½} − Uⁿ as it comes;
    # cdyn runs it so with time.reconstruct = false (by default it replaces the massless
    # part of U^{n+1} by the solution of eq. (14), docs/schemes.md).
    history, summary = cdyn_run(cdyn, os.path.join(work, "run"),
                                sets=("mesh.n=10", "output.fields=false", "time.reconstruct=false"))
    m = re.search(r"N_W = (\d+) free dofs .*, N_H = (\d+) cells", text)
    check(m is not None and (int(m.group(1)), int(m.group(2))) == (summary["n_free"], summary["n_velocity"]),
          "N_W and N_H as summary.json n_free, n_velocity")
    wp = summary["wellposed"]
    m = re.search(r"rank B = (\d+), dim Ker B = N_W - rank B = (\d+)", text)
    check(m is not None and int(m.group(2)) == wp["dim_ker_B"] == wp["n_g"] > 0,
          f"dim Ker B = {wp['dim_ker_B']} (summary.json wellposed), one direction per constraint: M singular")
    m = re.search(r"\|Mz\| = (\S+),", text)
    check(m is not None and float(m.group(1)) < 1e-15, "the hand-made z is in Ker M (|Mz| < 1e-15, z of size 1)")
    check_energy_trace(text, history, 9, BY_HAND)  # every 100 steps of 800
    m = re.search(r"max over t of \|J - J0\|/\|J0\| = (\S+), max violation of u\(a\) >= 0 .* = (\S+)", text)
    check(m is not None, "the energy balance line")
    # 4 printed digits.
    close(float(m.group(1)), summary["E_rel_drift"], 1e-3, "max drift as summary.json E_rel_drift")
    close(float(m.group(2)), summary["max_violation"], 1e-3, "max violation as summary.json max_violation")


if __name__ == "__main__":
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    number, exe, cdyn, src, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    {"1": example1, "2": example2, "3": example3, "4": example4, "5": example5, "6": example6}[number](exe, cdyn, src, work)
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        sys.exit(1)
