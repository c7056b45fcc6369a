#!/usr/bin/env python3
"""plot_study.py — the work-precision plot of a `cdyn study`, from its study.csv.

Usage: python3 scripts/plot_study.py STUDY_DIR

Writes STUDY_DIR/work_precision.png: the error of each run against its wall time
(the time loop, wall_s), log-log, one curve per method.  The columns of study.csv
before n_dofs are the varied keys; a method is one combination of the varied keys
other than the refinement keys mesh.n, mesh.file and time.dt (e.g. method.pair and
time.scheme): the refinements of a method are the points along its curve, each
labelled with its resolution.  Runs without an error (the finest run, which is the
reference; failed and interrupted runs) are left out.  docs/outputs.md defines the
errors.  `cdyn study` runs a copy of this file compiled into the binary.

Exit status 3 when matplotlib cannot be imported (plots are optional); Ctrl-C ends it
quietly with status 130.
"""
import csv
import math
import os
import signal
import sys

# Ctrl-C (the terminal signals cdyn and this script together): quietly, at once.
signal.signal(signal.SIGINT, lambda signum, frame: sys.exit(130))

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    if sys.argv[0] != "-c":  # run by hand (cdyn runs it with -c and prints its own note)
        print(f"{sys.argv[0]}: matplotlib is missing (Debian: python3-matplotlib)", file=sys.stderr)
    sys.exit(3)

RESOLUTION_KEYS = ("mesh.n", "mesh.file", "time.dt")


def number(text):
    try:
        x = float(text)
    except ValueError:
        return math.nan
    return x


def resolution_label(key, value):
    """"n=20", "dt=0.001", "file=disk_2.msh" (the file's name, not its path)."""
    if key == "mesh.file":
        value = os.path.basename(value.strip("\"'"))
    return f"{key.split('.')[-1]}={value}"


def error_label(measure):
    """The y axis for study.csv's error_measure (docs/outputs.md, "The error of a run")."""
    if measure == "exact":
        return "‖u_h(T) − u(T)‖_L2 (exact solution)"
    if measure == "energy":
        return "energy drift max |J − J0| / E_scale"
    if measure.startswith("probe:"):
        _, probe, column = (measure.split(":") + ["u"])[:3]
        return f"max_t |{column}@{probe} − finest| / max_t |finest|"
    return "error"


def figure(study_dir):
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
        label = " ".join(resolution_label(k, r[k]) for k in resolution_keys)
        curves.setdefault(method, []).append((wall, err, label))

    fig, ax = plt.subplots(figsize=(8.5, 5))
    for method, points in curves.items():
        points.sort()
        ax.loglog([p[0] for p in points], [p[1] for p in points], "o-", label=method)
        for wall, err, label in points:
            if label:
                ax.annotate(label, (wall, err), textcoords="offset points", xytext=(4, 4), fontsize=7)
    measures = sorted({r.get("error_measure", "") for r in rows})
    ax.set_ylabel(error_label(measures[0]) if len(measures) == 1 else "error")
    ax.set_xlabel("wall time of the time loop [s]")
    ax.set_title("work-precision: " + os.path.basename(os.path.normpath(study_dir)))
    ax.grid(True, which="both", alpha=0.3)
    if curves:  # outside the axes, on the right: it covers no curve
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=8)
    return fig


def main(study_dir):
    fig = figure(study_dir)
    path = os.path.join(study_dir, "work_precision.png")
    temporary = path + ".tmp"  # renamed when complete: never half an image
    try:
        fig.tight_layout()
        fig.savefig(temporary, dpi=110, format="png", bbox_inches="tight")
        os.replace(temporary, path)
    finally:
        plt.close(fig)
        if os.path.exists(temporary):
            os.remove(temporary)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
