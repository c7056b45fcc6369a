"""The commands of the ``cdyn`` program, from Python: run, study, wellposed, simulation.

Each runs the command line's own code (apps/cdyn, compiled into cdyn._cdyn) on a scene
given as a file, a dict or nothing (the embedded default: the seed's membrane), with
``--set``-style overrides, and returns what it wrote as numpy arrays and dicts: the
numbers are those of ``cdyn run`` bit for bit (history.csv carries 17 significant digits,
the field files raw doubles).  Bad input raises cdyn.InputError, a numerical failure
cdyn.NumericalError, with the command line's one-line message.
"""

import csv
import json
import os
import re
import warnings
import xml.etree.ElementTree as ElementTree

import numpy as np

from . import _cdyn
from .scenes import command_line_value, overrides, source


def run(scene=None, set=None, out=None, fields=True):
    """`cdyn run`: integrate a scene in time.

    scene: a scene file (path), a dict with a scene file's keys, or None for the embedded
    default.  set: overrides, {key: value} or ["key=value", ...] as --set.  out: the
    output directory (default out/<scene name>, as the command line).  Plots are off
    unless set asks for them (output.plots = true).  fields: read the field files back.

    Returns {'history': {column: array}, 'summary': dict, 'fields': dict or None,
    'out': path}; see docs/python.md.
    """
    path, text = source(scene)
    sets = ["output.plots=false"] + overrides(set)
    if out is None:
        out = os.path.join("out", _cdyn._scene_name(path, text, sets))
    try:
        status = _cdyn._run_command(path, text, sets, os.fspath(out))
    except _cdyn.NumericalError:
        # No summary.json to hold the warnings (often why it failed): the scene's own.
        warn(_cdyn._simulation(path, text, sets).warnings)
        raise
    result = {"history": read_history(os.path.join(out, "history.csv")),
              "summary": read_json(os.path.join(out, "summary.json")),
              "fields": None, "out": os.fspath(out)}
    warn(result["summary"]["warnings"])
    if status == 130:
        warn([f"interrupted: the results in {out} are partial"])
    if fields and os.path.exists(os.path.join(out, "fields.pvd")):
        result["fields"] = read_fields(out)
    return result


def warn(messages):
    """The run's warnings (`cdyn: warning: ...` on the command line) as RuntimeWarnings."""
    for w in messages:
        warnings.warn(w, RuntimeWarning, stacklevel=3)


def study(scene=None, vary=None, set=None, out=None, error="auto", fields=False):
    """`cdyn study`: one run per combination of the varied values.

    vary: {key: [v1, v2, ...]} or ["key=v1,v2,...", ...] as --vary (the last key changes
    fastest).  error: the error measure (auto, exact, energy, probe:NAME[:COLUMN]).
    Returns {'table': {column: array} of study.csv, 'runs': [run directory, ...],
    'out': path}.
    """
    path, text = source(scene)
    if isinstance(vary, dict):
        varies = [f"{k}=" + ",".join(command_line_value(v, k) for v in values) for k, values in vary.items()]
    else:
        varies = [vary] if isinstance(vary, str) else list(vary or [])
    if not varies:
        raise _cdyn.InputError("--vary: give at least one key and its values")
    sets = overrides(set)
    if out is None:
        out = os.path.join("out", _cdyn._scene_name(path, text, sets) + "-study")
    status = _cdyn._study_command(path, text, varies, sets, os.fspath(out), error, fields)
    table = read_csv(os.path.join(out, "study.csv"))
    if status == 130:
        warn([f"interrupted: study.csv in {out} holds the runs done"])
    return {"table": table, "runs": [os.path.join(out, r) for r in table.get("run", [])], "out": os.fspath(out)}


def wellposed(scene=None, set=None):
    """`cdyn wellposed --json`: condition (12) on the scene's mesh and constraints, one row
    (a dict: pair, N_W, N_H, dim_ker_B, N_g, beta, satisfied, method, or not_computed)
    per pair and classical mass model."""
    path, text = source(scene)
    return _cdyn._wellposed_rows(path, text, overrides(set))


def simulation(scene=None, set=None):
    """What `cdyn run` integrates, built by its code: a cdyn.Simulation with the scene's
    mesh, problem, solver, scheme and initial state, to step by hand."""
    path, text = source(scene)
    return _cdyn._simulation(path, text, overrides(set))


def scene_text(scene=None, set=None):
    """The scene as the command line reads it (overrides applied), as TOML text."""
    path, text = source(scene)
    return _cdyn._scene_text(path, text, overrides(set))


# ----- reading a run's files back (docs/outputs.md) --------------------------------------

def read_json(path):
    with open(path) as f:
        return json.load(f)


def read_history(path):
    """history.csv as {column: float array} (step as integers)."""
    with open(path) as f:
        header = f.readline().strip().split(",")
        data = np.loadtxt(f, delimiter=",", ndmin=2)
    columns = {name: data[:, k] for k, name in enumerate(header)}
    columns["step"] = columns["step"].astype(int)
    return columns


def read_csv(path):
    """A CSV file as {column: array}: numbers where every value is one (empty: nan), else str."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    table = {}
    for k, name in enumerate(header):
        values = [r[k] for r in rows]
        try:
            table[name] = np.array([float(v) if v != "" else np.nan for v in values])
        except ValueError:
            table[name] = np.array(values)
    return table


def read_fields(out):
    """fields.pvd and fields/*.vtu as arrays: 't', 'step' (one per frame), 'points',
    'cells', and each point array ('u', 'v', 'lambda', ...) as frames × vertices
    (× components); the cell arrays of elasticity under 'cell_data'.  Read by meshio."""
    try:
        import meshio
    except ImportError:
        warnings.warn("no meshio (python3-meshio): the fields are not read", RuntimeWarning, stacklevel=3)
        return None
    frames = [(float(d.get("timestep")), d.get("file"))
              for d in ElementTree.parse(os.path.join(out, "fields.pvd")).iter("DataSet")]
    meshes = [meshio.read(os.path.join(out, file)) for _, file in frames]
    fields = {"t": np.array([t for t, _ in frames]),
              "step": np.array([int(re.search(r"(\d+)\.vtu$", file).group(1)) for _, file in frames]),
              "points": meshes[0].points, "cells": meshes[0].cells[0].data, "cell_data": {}}
    def frames_of(arrays):  # frames × entities, × components unless there is one
        a = np.stack(arrays)
        return a[..., 0] if a.ndim == 3 and a.shape[2] == 1 else a
    for name in meshes[0].point_data:
        fields[name] = frames_of([m.point_data[name] for m in meshes])
    for name in meshes[0].cell_data:
        fields["cell_data"][name] = frames_of([m.cell_data[name][0] for m in meshes])
    return fields
