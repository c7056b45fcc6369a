#!/usr/bin/python3
"""plot_experiments.py — the figures and the table of docs/experiments.md.

Reads the runs that scripts/experiments.sh wrote (one folder per run with history.csv
and summary.json) and writes PNG figures into the given folder; prints the table as
Markdown on stdout.

    /usr/bin/python3 scripts/plot_experiments.py out/experiments docs/img
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(folder, name):
    path = os.path.join(folder, name)
    with open(os.path.join(path, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    cols = {k: [float(r[k]) for r in rows] for k in rows[0]}
    with open(os.path.join(path, "summary.json")) as f:
        summary = json.load(f)
    return cols, summary


def relative_energy(h, s):
    return [x / s["E0"] for x in h["E_total"]]


def panels(folder, runs, columns, title, out):
    """One figure: a panel per column (ylabel, values(history, summary), log scale?),
    a curve per run (folder name, legend label)."""
    fig, ax = plt.subplots(1, len(columns), figsize=(5 * len(columns) + 2, 4))
    for name, label in runs:
        h, s = load(folder, name)
        for a, (_, values, _) in zip(ax, columns):
            a.plot(h["t"], values(h, s), label=label)
    for a, (ylabel, _, log) in zip(ax, columns):
        a.set_ylabel(ylabel)
        if log:
            a.set_yscale("log")
        a.set_xlabel("t")
        a.grid(True, alpha=0.3)
    ax[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


MEMBRANE = [("J(t) / J(0)", relative_energy, True),
            ("u at the centre", lambda h, s: h["u@centre"], False),
            ("λ at the centre (seed's sign, ≤ 0)", lambda h, s: h["lambda@centre"], False)]
OSCILLATOR = [("u(t)", lambda h, s: h["u@mass"], False), ("J(t) / J(0)", relative_energy, True)]


def table(folder):
    print("| run | pair / mass | scheme | dofs | steps | \\|J(T) − J0\\|/J0 | max \\|J − J0\\|/J0 | max violation | QP iters/step | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name in sorted(os.listdir(folder)):
        if not os.path.exists(os.path.join(folder, name, "summary.json")):
            continue
        _, s = load(folder, name)
        err = abs(s["E_final"] - s["E0"]) / abs(s["E0"])
        print(f"| {name} | {s['pair']} | {s['scheme']} | {s['n_dofs']} | {s['n_steps']} | {err:.2e} | "
              f"{s['E_rel_drift']:.2e} | {s['max_violation']:.1e} | {s['qp_iters_mean']:.2f} | {s['wall_s']:.3f} |")


def main():
    folder, img = sys.argv[1], sys.argv[2]
    os.makedirs(img, exist_ok=True)
    pairs = ["P1b_P0", "P1_P0", "P1_P1", "P1b_P1", "P2_P1"]
    panels(folder, [(f"membrane_midpoint_{p}", p.replace("b", "+").replace("_", "/")) for p in pairs], MEMBRANE,
           "Membrane, h = 0.1, dt = 0.001, midpoint (constraint on the half step)",
           os.path.join(img, "experiments_midpoint_pairs.png"))
    panels(folder, [("membrane_backward_euler_P1b_P0", "P1+/P0"), ("membrane_backward_euler_P1_P0", "P1/P0")],
           MEMBRANE, "Membrane, h = 0.1, dt = 0.001, backward Euler", os.path.join(img, "experiments_backward_euler.png"))
    panels(folder, [("membrane_midpoint_P1b_P0", "P1+/P0, h = 0.1"),
                    ("membrane_midpoint_P1b_P0_h005", "P1+/P0, h = 0.05"),
                    ("membrane_energy_conserving_consistent", "consistent, energy_conserving"),
                    ("membrane_paoli_schatzman_lumped", "lumped, paoli_schatzman e = 0 (dt = 0.0005)")], MEMBRANE,
           "Membrane: the flagship pair against the classical schemes", os.path.join(img, "experiments_classical.png"))
    panels(folder, [(f"oscillator_{s}", s) for s in
                    ["midpoint", "midpoint_end", "backward_euler", "newmark", "energy_conserving"]] +
           [(f"oscillator_paoli_schatzman_e{e}", f"paoli_schatzman e = {e}") for e in ["0", "0.5", "1"]], OSCILLATOR,
           "The one-dof oscillator: u = a|cos t| after the impact, a chosen by the scheme",
           os.path.join(img, "experiments_oscillator.png"))
    table(folder)


if __name__ == "__main__":
    main()
