#!/usr/bin/env python3
"""plot_study.py — the work-precision plot of a `cdyn study`, from its study.csv.

Usage: python3 scripts/plot_study.py STUDY_DIR

Writes STUDY_DIR/work_precision.png: the error of each run against its wall time
(the time loop, wall_s), log-log, one curve per method.  The columns of study.csv
before n_dofs are the varied keys; a method is one combination of the varied keys
other than the resolution keys mesh.n and time.dt (e.g. method.pair and
time.scheme), and each point is labelled with its resolution.  Runs without an error
(the finest run, which is the reference; failed runs) are left out.  docs/outputs.md
defines the errors.  `cdyn study` runs a copy of this file compiled into the binary.

Exit status 3 when matplotlib cannot be imported (plots are optional).
"""
import csv
import math
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    if sys.argv[0] != "-c":  # run by hand (cdyn runs it with -c and prints its own note)
        print(f"{sys.argv[0]}: matplotlib is missing (Debian: python3-matplotlib)", file=sys.stderr)
    sys.exit(3)

RESOLUTION_KEYS = ("mesh.n", "time.dt")


def number(text):
    try:
        x = float(text)
    except ValueError:
        return math.nan
    return x


def main(study_dir):
    with open(os.path.join(study_dir, "study.csv"), newline="") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames
        rows = list(reader)
    varied = header[: header.index("n_dofs")]
    method_keys = [k for k in varied if k not in RESOLUTION_KEYS]
    resolution_keys = [k for k in varied if k in RESOLUTION_KEYS]

    curves = {}
    for r in rows:
        err, wall = number(r["error"]), number(r["wall_s"])
        if not (err > 0 and wall > 0):  # NaN, empty, zero: nothing to draw on log axes
            continue
        method = ", ".join(f"{k}={r[k]}" for k in method_keys) or "all runs"
        label = " ".join(f"{k.split('.')[-1]}={r[k]}" for k in resolution_keys)
        curves.setdefault(method, []).append((wall, err, label))

    fig, ax = plt.subplots(figsize=(7, 5))
    for method, points in curves.items():
        points.sort()
        ax.loglog([p[0] for p in points], [p[1] for p in points], "o-", label=method)
        for wall, err, label in points:
            if label:
                ax.annotate(label, (wall, err), textcoords="offset points", xytext=(4, 4), fontsize=7)
    kinds = sorted({r["error_kind"] for r in rows if r["error_kind"] in ("exact", "finest")})
    ylabel = {"exact": "error against the exact solution", "finest": "error against the finest run"}
    ax.set_ylabel(" / ".join(ylabel[k] for k in kinds) or "error")
    ax.set_xlabel("wall time of the time loop [s]")
    ax.set_title("work-precision: " + os.path.basename(os.path.normpath(study_dir)))
    ax.grid(True, which="both", alpha=0.3)
    if curves:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(study_dir, "work_precision.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
