#!/usr/bin/env python3
"""plot_run.py — the plots of one `cdyn run`, from its history.csv and summary.json.

Usage: python3 scripts/plot_run.py RUN_DIR

Writes RUN_DIR/plots/:
  energy.png   E_kin, E_pot and E_total = J against t (seed, Theorem 2), and below
               the drift (J - J0)/E_scale (summary.json's E_scale: |J0|, or for a run
               from rest the energy it exchanges), where conservation shows (or not);
               with Rayleigh damping also the dissipated work W_d, with friction the
               friction work W_f, and the drift of J + W_d + W_f;
  probes.png   u@P and lambda@P against t for every probe P (when the scene has any);
  contact.png  the number of active constraints per step and, at the probes, the
               contact force -lambda@P (lambda <= 0 is the seed's multiplier);
  contact_pressure.png  (elasticity runs, from contact.csv) the contact pressure along
               Gamma_C over time: a space-time image and the profiles at a few times,
               where the spurious oscillations of a standard mass show against the
               smooth pressure of the well-posed methods; limited to the time window
               of the contact;
  friction.png (runs with friction, from contact.csv) the tangential force, the slip and
               the stick/slip status of every friction vertex along Gamma_C over time.
The axes carry the scene's units (its `units` key, in summary.json); the legends sit
outside the axes, where they cover no curve.  docs/outputs.md describes the columns.  `cdyn run` runs a copy of this file compiled
into the binary (apps/CMakeLists.txt), so edits here take effect at the next build;
running it by hand remakes the plots of an existing run.

Exit status 3 when matplotlib cannot be imported (cdyn then tries another python3, or
prints a note): plots are optional, never an error of the run.  Ctrl-C ends it quietly
with status 130 (no traceback, no half-written image: each is written under a
temporary name and renamed).
"""
import csv
import json
import os
import signal
import sys

# Ctrl-C (the terminal signals cdyn and this script together): quietly, at once.
signal.signal(signal.SIGINT, lambda signum, frame: sys.exit(130))

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


def unit(summary, quantity):
    """ " [unit]" of a quantity in the scene's units (summary.json "units": length, force,
    time), "" without them.  Plane-strain elasticity gives energies and forces per unit
    thickness (N·mm/mm, N/mm), elasticity in space whole ones (N·mm, N); the scalar
    models' are the model's own (F·L, F)."""
    u = summary.get("units")
    if not u:
        return ""
    L, F, T = u["length"], u["force"], u["time"]
    per = "/" + L if summary.get("model") == "elasticity" and summary.get("dim", 2) == 2 else ""
    text = {"length": L, "time": T, "energy": F + "·" + L + per, "force": F + per, "pressure": F + "/" + L + "²",
            "velocity": L + "/" + T}[quantity]
    return " [" + text + "]"


def legend(ax):
    """A legend outside the axes, on the right: it covers no curve."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=8)


def plot_energy(h, summary):
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8.5, 6), gridspec_kw={"height_ratios": [2, 1]})
    t = h["t"]
    top.plot(t, h["E_kin"], label="E_kin = ½VᵀCV")
    top.plot(t, h["E_pot"], label="E_pot = ½UᵀAU − LᵀU")
    top.plot(t, h["E_total"], "k", label="E_total = J")
    # With Rayleigh damping and friction the balance is J + W_d + W_f = J0: the works
    # taken (history.csv's `dissipated`, `friction_work`) and the balance are drawn, and
    # the drift is that of the balance.
    works = [(key, symbol, text) for key, symbol, text in
             (("dissipated", "W_d", "work of the damping"), ("friction_work", "W_f", "work of friction")) if key in h]
    balance = list(h["E_total"])
    name = "J"
    for key, symbol, text in works:
        top.plot(t, h[key], ":", label=f"{symbol}, {text}")
        balance = [b + w for b, w in zip(balance, h[key])]
        name += " + " + symbol
    if works:
        top.plot(t, balance, "k--", label=name)
    top.set_ylabel("energy" + unit(summary, "energy"))
    legend(top)
    top.set_title(title(summary))
    E0 = h["E_total"][0]
    # summary.json's E_scale: |J0|, or for a start from rest (J0 = 0) the energy the run
    # exchanges; never a division by zero, never an absolute drift under a relative label.
    scale = summary.get("E_scale") or abs(E0) or 1.0
    bottom.plot(t, [(e - E0) / scale for e in balance], "k")
    if scale == abs(E0):
        bottom.set_ylabel("(%s − J0)/|J0|" % name)
    else:
        bottom.set_ylabel("(%s − J0)/E_scale" % name)
        bottom.set_title("E_scale = max(E_kin + |E_pot|)/2 = %.4g (J0 = %.3g)" % (scale, E0), fontsize=8)
    bottom.set_xlabel("t" + unit(summary, "time"))
    bottom.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
    return fig


def probe_names(h):
    return [k[len("lambda@"):] for k in h if k.startswith("lambda@")]


def displacement_columns(h, p):
    """u@P for a scalar field, ux@P and uy@P for elasticity."""
    return [c for c in ("u@" + p, "ux@" + p, "uy@" + p) if c in h]


def plot_probes(h, summary):
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8.5, 6))
    for p in probe_names(h):
        for c in displacement_columns(h, p):
            top.plot(h["t"], h[c], label=c)
        bottom.plot(h["t"], h["lambda@" + p], label="λ@" + p)
    top.set_ylabel("displacement u" + unit(summary, "length"))
    legend(top)
    top.set_title(title(summary))
    bottom.set_ylabel("multiplier λ ≤ 0" + unit(summary, "force"))
    bottom.set_xlabel("t" + unit(summary, "time"))
    legend(bottom)
    return fig


def plot_contact(h, summary):
    names = probe_names(h)
    fig, axes = plt.subplots(2 if names else 1, 1, sharex=True, figsize=(8.5, 6 if names else 3.5), squeeze=False)
    top = axes[0][0]
    top.step(h["t"], h["active"], where="post", color="C3")
    top.set_ylabel("active constraints")
    top.set_title(title(summary))
    if names:
        bottom = axes[1][0]
        for p in names:
            bottom.plot(h["t"], [-l for l in h["lambda@" + p]], label="−λ@" + p)
        bottom.set_ylabel("contact force at the probe" + unit(summary, "force"))
        legend(bottom)
    axes[-1][0].set_xlabel("t" + unit(summary, "time"))
    return fig


def read_contact(path, columns=("pressure",)):
    """contact.csv as (times, s, {column: values[time][vertex]}), the vertices in the
    file's order (sorted by s); None when a column is missing."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if rows and any(c not in rows[0] for c in columns):
        return None
    times, s, values = [], [], {c: [] for c in columns}
    for r in rows:
        t = float(r["t"])
        if not times or t != times[-1]:
            times.append(t)
            for c in columns:
                values[c].append([])
        if len(times) == 1:
            s.append(float(r["s"]))
        for c in columns:
            values[c][-1].append(float(r[c]))
    return times, s, values


def plot_contact_pressure(contact_csv, summary):
    times, s, values = read_contact(contact_csv)
    pressure = values["pressure"]
    if not s or len(times) < 2:
        return None
    # Contact means a pressure above the QP's round-off (about 1e-11 of the peak): the
    # part of Γ_C that touches at some time, with a margin of two vertices.
    peak = max(max(p) for p in pressure)
    floor = 1e-8 * peak if peak > 0 else float("inf")
    touched = [i for i in range(len(s)) if any(p[i] > floor for p in pressure)] or list(range(len(s)))
    lo, hi = max(min(touched) - 2, 0), min(max(touched) + 2, len(s) - 1)
    s = s[lo : hi + 1]
    pressure = [p[lo : hi + 1] for p in pressure]
    # And the time window of the contact (a tenth of it, at least two frames, either
    # side): a short impact in a long run would otherwise be a line across the image.
    in_contact = [k for k, p in enumerate(pressure) if max(p) > floor]
    if in_contact:
        first, last = in_contact[0], in_contact[-1]
        margin = max(2, (last - first) // 10)
        k0, k1 = max(first - margin, 0), min(last + margin, len(times) - 1)
    else:
        k0, k1 = 0, len(times) - 1
    window = times[k0 : k1 + 1]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.5), gridspec_kw={"width_ratios": [3, 2]})
    image = left.pcolormesh(s, window, pressure[k0 : k1 + 1], shading="nearest", cmap="viridis")
    fig.colorbar(image, ax=left, label="contact pressure" + unit(summary, "pressure"))
    left.set_xlabel("position along the plane s" + unit(summary, "length"))
    left.set_ylabel("t" + unit(summary, "time"))
    left.set_title(title(summary), fontsize=9)
    # Profiles at the time of the peak pressure and at a few times across the contact.
    if in_contact:
        at_peak = max(in_contact, key=lambda k: max(pressure[k]))
        picks = sorted({first + (last - first) * q // 4 for q in range(1, 4)} | {at_peak})
        for k in picks:
            right.plot(s, pressure[k], marker=".", label="t = %.4g" % times[k])
        legend(right)
    right.set_xlabel("position along the plane s" + unit(summary, "length"))
    right.set_ylabel("contact pressure" + unit(summary, "pressure"))
    return fig


def plot_friction(contact_csv, summary):
    """The friction vertices' tangential force, slip and status against s and t."""
    read = read_contact(contact_csv, ("tangential_force", "slip", "status"))
    if read is None or not read[1] or len(read[0]) < 2:
        return None
    times, s, v = read
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    panels = [("tangential_force", "tangential force λ_T (along t; in space |λ_T|)" + unit(summary, "force"), "coolwarm"),
              ("slip", "slip Uⁿ⁺¹_T − Uⁿ_T (along t; in space its length)" + unit(summary, "length"), "coolwarm")]
    for ax, (column, label, cmap) in zip(axes, panels):
        data = v[column]
        bound = max(max(abs(x) for x in row) for row in data) or 1.0
        image = ax.pcolormesh(s, times, data, shading="nearest", cmap=cmap, vmin=-bound, vmax=bound)
        fig.colorbar(image, ax=ax, label=label)
    # status: −1 no friction, 0 open, 1 stick, 2 slip (docs/outputs.md)
    states = matplotlib.colors.ListedColormap(["lightgrey", "white", "tab:blue", "tab:red"])
    image = axes[2].pcolormesh(s, times, v["status"], shading="nearest", cmap=states, vmin=-1.5, vmax=2.5)
    bar = fig.colorbar(image, ax=axes[2], ticks=[-1, 0, 1, 2])
    bar.ax.set_yticklabels(["no friction", "open", "stick", "slip"])
    for ax in axes:
        ax.set_xlabel("position along Γ_C s" + unit(summary, "length"))
        ax.set_ylabel("t" + unit(summary, "time"))
    axes[0].set_title(title(summary), fontsize=9)
    return fig


def figures(run_dir):
    """The figures of a run, by file name (tests/cli/check_plots.py looks at them)."""
    h = read_history(os.path.join(run_dir, "history.csv"))
    with open(os.path.join(run_dir, "summary.json")) as f:
        summary = json.load(f)
    yield "energy.png", plot_energy(h, summary)
    if probe_names(h):
        yield "probes.png", plot_probes(h, summary)
    yield "contact.png", plot_contact(h, summary)
    contact_csv = os.path.join(run_dir, "contact.csv")
    if os.path.isfile(contact_csv):
        fig = plot_contact_pressure(contact_csv, summary)
        if fig is not None:
            yield "contact_pressure.png", fig
        fig = plot_friction(contact_csv, summary)
        if fig is not None:
            yield "friction.png", fig


def save(fig, path):
    """Writes the image under a temporary name, then renames it: never half an image."""
    temporary = path + ".tmp"
    try:
        fig.tight_layout()
        fig.savefig(temporary, dpi=110, format="png", bbox_inches="tight")  # tight: the outside legends
        os.replace(temporary, path)
    finally:
        plt.close(fig)
        if os.path.exists(temporary):
            os.remove(temporary)


def main(run_dir):
    out = os.path.join(run_dir, "plots")
    os.makedirs(out, exist_ok=True)
    for name, fig in figures(run_dir):
        save(fig, os.path.join(out, name))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
