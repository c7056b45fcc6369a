#!/usr/bin/env python3
"""check_plots.py — the plots a reader can use (scripts/plot_run.py, plot_study.py).

Usage: check_plots.py CDYN SOURCE_DIR WORKDIR      (skipped, status 77, without matplotlib)

The figures are built by the scripts' own functions (the copy compiled into cdyn is
the same file) and looked at:
- the axes carry the scene's units (`units = "mm, N, s"` of the elasticity scenes,
  in summary.json): t [s], u [mm], energies [N·mm/mm] and forces [N/mm] per unit
  thickness, the contact pressure [N/mm²];
- no legend covers a curve: each lies outside its axes (drawn, their boxes do not meet);
- the Hertz run starts at rest: its drift is drawn against E_scale, not |J0| = 0;
- contact_pressure.png shows the time window of the contact, not the whole run: the
  disk touches the plane for t in [0.5, 6.5] ms of its 10 ms;
- with friction, friction.png shows the tangential force, the slip and the status of
  each vertex over time, and energy.png the friction work W_f and the balance J + W_f;
  in space the forces and energies are whole ones ([N], [N·m]), not per thickness;
- work_precision.png draws the refinements of a method (mesh.file, mesh.n, time.dt)
  along one curve: a study over two meshes and two schemes has two curves, not four.
"""
import csv
import importlib.util
import json
import os
import shutil
import subprocess
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
except ImportError:
    print("check_plots: skipped (no matplotlib)")
    sys.exit(77)

from cli_helpers import check, failures

cdyn, src, work = sys.argv[1:4]


def module(name):
    spec = importlib.util.spec_from_file_location(name, os.path.join(src, "scripts", name + ".py"))
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


plot_run, plot_study = module("plot_run"), module("plot_study")


def run(scene, out, *sets):
    out = os.path.join(work, out)
    shutil.rmtree(out, ignore_errors=True)
    args = [cdyn, "run", os.path.join(src, "data", "scenes", scene), "--out", out, "--quiet",
            "--set", "output.plots=false", "--set", "output.fields=false"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return out, json.load(f)


def legends_outside(name, fig):
    fig.canvas.draw()
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None:
            continue
        box, frame = legend.get_window_extent(), ax.get_window_extent()
        check(box.x0 >= frame.x1 or box.y0 >= frame.y1, f"{name}: the legend of '{ax.get_ylabel()}' lies outside its axes")


out, s = run("hertz.toml", "plots_hertz")
check(s["units"] == {"length": "mm", "force": "N", "time": "s"}, f"hertz: summary.json units {s['units']}")
figures = dict(plot_run.figures(out))
energy = figures["energy.png"].axes
check(energy[0].get_ylabel() == "energy [N·mm/mm]" and energy[1].get_xlabel() == "t [s]",
      f"energy.png: '{energy[0].get_ylabel()}', '{energy[1].get_xlabel()}'")
check(energy[1].get_ylabel() == "(J − J0)/E_scale", f"energy.png (J0 = 0): '{energy[1].get_ylabel()}'")
probes = figures["probes.png"].axes
check(probes[0].get_ylabel() == "displacement u [mm]" and probes[1].get_ylabel() == "multiplier λ ≤ 0 [N/mm]",
      f"probes.png: '{probes[0].get_ylabel()}', '{probes[1].get_ylabel()}'")
for name, fig in figures.items():
    legends_outside("hertz " + name, fig)

out, s = run("disk.toml", "plots_disk")
figures = dict(plot_run.figures(out))
image = figures["contact_pressure.png"].axes[0]
t0, t1 = image.get_ylim()
impact = s["impact"]
check(image.get_ylabel() == "t [s]" and figures["contact_pressure.png"].axes[2].get_ylabel() == "contact pressure [N/mm²]",
      "contact_pressure.png: units")
check(t0 < impact["t_first_contact"] and impact["t_last_contact"] < t1 < 0.8 * s["T"],
      f"contact_pressure.png: t in [{t0:.4g}, {t1:.4g}] around the contact "
      f"[{impact['t_first_contact']:.4g}, {impact['t_last_contact']:.4g}] of T = {s['T']:.4g}")
for name, fig in figures.items():
    legends_outside("disk " + name, fig)

out, s = run("incline_block.toml", "plots_friction")
figures = dict(plot_run.figures(out))
check("friction.png" in figures, "friction.png is drawn for a run with friction")
bars = [a.get_ylabel() for a in figures["friction.png"].axes[3:]]
check(bars[0].startswith("tangential force") and bars[0].endswith("[N/m]") and bars[1].startswith("slip")
      and bars[1].endswith("[m]"), f"friction.png: colour bars {bars}")
status = figures["friction.png"].axes[5]
check([t.get_text() for t in status.get_yticklabels()] == ["no friction", "open", "stick", "slip"],
      "friction.png: the status's colours are named")
labels = figures["energy.png"].axes[0].get_legend_handles_labels()[1]
check("W_f, work of friction" in labels and "J + W_f" in labels and
      figures["energy.png"].axes[1].get_ylabel() == "(J + W_f − J0)/E_scale", f"energy.png with friction: {labels}")
for name, fig in figures.items():
    legends_outside("friction " + name, fig)
out, s = run("incline_block_3d.toml", "plots_friction_3d")
figures = dict(plot_run.figures(out))
check(figures["energy.png"].axes[0].get_ylabel() == "energy [N·m]" and
      figures["friction.png"].axes[3].get_ylabel().endswith("[N]"),
      f"in space, whole energies and forces: '{figures['energy.png'].axes[0].get_ylabel()}'")

# A study's table, written by hand: two meshes (files) for each of two schemes.
study = os.path.join(work, "plots_study")
os.makedirs(study, exist_ok=True)
with open(os.path.join(study, "study.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["time.scheme", "mesh.file", "n_dofs", "wall_s", "error", "error_kind", "error_measure", "partial", "run"])
    for k, (scheme, mesh) in enumerate([(s, m) for s in ("midpoint", "backward_euler") for m in ("/m/coarse.msh", "/m/fine.msh")]):
        w.writerow([scheme, mesh, 100, 0.1 * (k + 1), 0.01 / (k + 1), "finest", "probe:tip:u", "false", f"run_{k:03d}"])
fig = plot_study.figure(study)
ax = fig.axes[0]
labels = [t.get_text() for t in ax.get_legend().get_texts()]
check(labels == ["time.scheme=midpoint", "time.scheme=backward_euler"], f"work_precision.png: curves {labels}")
check({t.get_text() for t in ax.texts} == {"file=coarse.msh", "file=fine.msh"}, "work_precision.png: points labelled by mesh file")
check(ax.get_ylabel() == "max_t |u@tip − finest| / max_t |finest|", f"work_precision.png: '{ax.get_ylabel()}'")
legends_outside("work_precision.png", fig)

if failures:
    sys.exit("check_plots: FAILED: " + "; ".join(failures))
print("check_plots: ok")
