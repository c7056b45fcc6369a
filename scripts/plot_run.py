#!/usr/bin/env python3
"""plot_run.py — the plots of one `cdyn run`, from its history.csv and summary.json.

Usage: python3 scripts/plot_run.py RUN_DIR

Writes RUN_DIR/plots/:
  energy.png   E_kin, E_pot and E_total = J against t (seed, Theorem 2), and below
               the relative drift (J - J0)/|J0|, where conservation shows (or not);
  probes.png   u@P and lambda@P against t for every probe P (when the scene has any);
  contact.png  the number of active constraints per step and, at the probes, the
               contact force -lambda@P (lambda <= 0 is the seed's multiplier);
  contact_pressure.png  (elasticity runs, from contact.csv) the contact pressure along
               Gamma_C over time: a space-time image and the profiles at a few times,
               where the spurious oscillations of a standard mass show against the
               smooth pressure of the well-posed methods.
docs/outputs.md describes the columns.  `cdyn run` runs a copy of this file compiled
into the binary (apps/CMakeLists.txt), so edits here take effect at the next build;
running it by hand remakes the plots of an existing run.

Exit status 3 when matplotlib cannot be imported (cdyn then tries another python3, or
prints a note): plots are optional, never an error of the run.
"""
import csv
import json
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")  # files only, no display needed
    import matplotlib.pyplot as plt
except ImportError:
    if sys.argv[0] != "-c":  # run by hand (cdyn runs it with -c and prints its own note)
        print(f"{sys.argv[0]}: matplotlib is missing (Debian: python3-matplotlib)", file=sys.stderr)
    sys.exit(3)


def read_history(path):
    """The columns of history.csv as lists of floats, by header name."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in (rows[0].keys() if rows else [])}


def title(summary):
    return "{scene}: {pair}, {scheme}, dt = {dt:g}, {n_dofs} dofs".format(**summary)


def plot_energy(h, summary, path):
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 6), gridspec_kw={"height_ratios": [2, 1]})
    t = h["t"]
    top.plot(t, h["E_kin"], label="E_kin = ½VᵀCV")
    top.plot(t, h["E_pot"], label="E_pot = ½UᵀAU − LᵀU")
    top.plot(t, h["E_total"], "k", label="E_total = J")
    top.set_ylabel("energy")
    top.legend()
    top.set_title(title(summary))
    E0 = h["E_total"][0]
    scale = abs(E0) if E0 != 0 else 1.0
    bottom.plot(t, [(e - E0) / scale for e in h["E_total"]], "k")
    bottom.set_ylabel("(J − J0)/|J0|")
    bottom.set_xlabel("t")
    bottom.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def probe_names(h):
    return [k[len("lambda@"):] for k in h if k.startswith("lambda@")]


def displacement_columns(h, p):
    """u@P for a scalar field, ux@P and uy@P for elasticity."""
    return [c for c in ("u@" + p, "ux@" + p, "uy@" + p) if c in h]


def plot_probes(h, summary, path):
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    for p in probe_names(h):
        for c in displacement_columns(h, p):
            top.plot(h["t"], h[c], label=c)
        bottom.plot(h["t"], h["lambda@" + p], label="λ@" + p)
    top.set_ylabel("displacement u")
    top.legend()
    top.set_title(title(summary))
    bottom.set_ylabel("multiplier λ ≤ 0")
    bottom.set_xlabel("t")
    bottom.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_contact(h, summary, path):
    names = probe_names(h)
    fig, axes = plt.subplots(2 if names else 1, 1, sharex=True, figsize=(7, 6 if names else 3.5), squeeze=False)
    top = axes[0][0]
    top.step(h["t"], h["active"], where="post", color="C3")
    top.set_ylabel("active constraints")
    top.set_title(title(summary))
    if names:
        bottom = axes[1][0]
        for p in names:
            bottom.plot(h["t"], [-l for l in h["lambda@" + p]], label="−λ@" + p)
        bottom.set_ylabel("contact force at the probe")
        bottom.legend()
    axes[-1][0].set_xlabel("t")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def read_contact(path):
    """contact.csv as (times, s, pressure[time][vertex]), the vertices sorted by s."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    times, s, pressure = [], [], []
    for r in rows:
        t = float(r["t"])
        if not times or t != times[-1]:
            times.append(t)
            pressure.append([])
        if len(times) == 1:
            s.append(float(r["s"]))
        pressure[-1].append(float(r["pressure"]))
    return times, s, pressure


def plot_contact_pressure(contact_csv, summary, path):
    times, s, pressure = read_contact(contact_csv)
    if not s or len(times) < 2:
        return
    # Contact means a pressure above the QP's round-off (about 1e-11 of the peak): the
    # part of Γ_C that touches at some time, with a margin of two vertices.
    peak = max(max(p) for p in pressure)
    floor = 1e-8 * peak if peak > 0 else float("inf")
    touched = [i for i in range(len(s)) if any(p[i] > floor for p in pressure)] or list(range(len(s)))
    lo, hi = max(min(touched) - 2, 0), min(max(touched) + 2, len(s) - 1)
    s = s[lo : hi + 1]
    pressure = [p[lo : hi + 1] for p in pressure]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5), gridspec_kw={"width_ratios": [3, 2]})
    image = left.pcolormesh(s, times, pressure, shading="nearest", cmap="viridis")
    fig.colorbar(image, ax=left, label="contact pressure")
    left.set_xlabel("position along the plane s")
    left.set_ylabel("t")
    left.set_title(title(summary), fontsize=9)
    # Profiles at the time of the peak pressure and at a few times across the contact.
    in_contact = [k for k, p in enumerate(pressure) if max(p) > floor]
    if in_contact:
        first, last = in_contact[0], in_contact[-1]
        at_peak = max(in_contact, key=lambda k: max(pressure[k]))
        picks = sorted({first + (last - first) * q // 4 for q in range(1, 4)} | {at_peak})
        for k in picks:
            right.plot(s, pressure[k], marker=".", label="t = %.4g" % times[k])
        right.legend(fontsize=8)
    right.set_xlabel("position along the plane s")
    right.set_ylabel("contact pressure")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(run_dir):
    h = read_history(os.path.join(run_dir, "history.csv"))
    with open(os.path.join(run_dir, "summary.json")) as f:
        summary = json.load(f)
    out = os.path.join(run_dir, "plots")
    os.makedirs(out, exist_ok=True)
    plot_energy(h, summary, os.path.join(out, "energy.png"))
    if probe_names(h):
        plot_probes(h, summary, os.path.join(out, "probes.png"))
    plot_contact(h, summary, os.path.join(out, "contact.png"))
    contact_csv = os.path.join(run_dir, "contact.csv")
    if os.path.isfile(contact_csv):
        plot_contact_pressure(contact_csv, summary, os.path.join(out, "contact_pressure.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
