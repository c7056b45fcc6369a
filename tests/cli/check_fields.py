#!/usr/bin/env python3
"""check_fields.py — the VTU files of `cdyn run`, read by an independent reader (meshio).

Usage: check_fields.py CDYN WORKDIR LSHAPE_SCENE

Three short runs, each file read with python3-meshio:
  - the default membrane on a 6 x 6 mesh: 49 points at z = 0, 72 triangles, u = 0.02
    (the Dirichlet value) on the boundary points and everywhere at step 0, v = 0 and
    lambda = 0 at step 0, lambda <= 0 (to round-off), and u, v, lambda at the centre
    vertex equal to history.csv's probe columns at the same step;
  - a 1D bar: VTK_LINE cells, n + 1 points on the x axis, u = 0 at the clamped end;
  - data/scenes/lshape.toml run from another directory (its mesh.file is relative to
    the scene file): as many points as `cdyn mesh` reports vertices, u = 0.02 on the
    physical group "outer" and not on the free re-entrant sides;
  - data/scenes/ramp.toml (a plane inclined by 30°, whose contact unknowns are rotated
    normal/tangential components): at the vertices in contact the lambda vector is the
    seed's λ_N n, parallel to the plane's normal n (|λ × n| ≤ 1e-12 |λ|: round-off of the
    rotation) with λ·n < 0; written in the rotated components it would point along x;
  - the same ramp run's elasticity arrays (docs/outputs.md): point and cell data
    "sigma", "epsilon" (3 x 3 tensors, 9 components, symmetric, ε_zz = 0), "von_mises";
    in every cell σ = λ tr ε I + 2μ ε with the scene's λ = 300, μ = 150 (σ_zz = λ tr ε,
    plane strain) and von_mises that of σ; the point values are the area-weighted
    averages of the cell values around each vertex (recomputed here); the point data
    "contact_pressure" is contact.csv's pressure at the constrained vertices of the same
    step and 0 elsewhere; the cell data "region" is 0 (the physical surface "disk").
Exit status 77 (skipped) when meshio or numpy is missing.
"""
import csv
import glob
import os
import re
import shutil
import subprocess
import sys

from cli_helpers import import_meshio

meshio, np = import_meshio("check_fields")

cdyn, work, lshape = sys.argv[1], sys.argv[2], sys.argv[3]


def run(out, *sets, scene=None, cwd=None):
    args = [cdyn, "run"] + ([scene] if scene else []) + ["--quiet", "--out", out, "--set", "output.plots=false"]
    for s in sets:
        args += ["--set", s]
    shutil.rmtree(out, ignore_errors=True)
    subprocess.run(args, check=True, cwd=cwd)
    with open(os.path.join(out, "history.csv")) as f:
        rows = {int(r["step"]): r for r in csv.DictReader(f)}
    files = sorted(glob.glob(os.path.join(out, "fields", "step_*.vtu")))
    return rows, {int(re.search(r"step_(\d+)\.vtu", f).group(1)): meshio.read(f) for f in files}


def one_cell_block(m, kind):
    assert len(m.cells) == 1 and m.cells[0].type == kind, m.cells
    return m.cells[0].data


# 2D: the default membrane on a small mesh, fields every 5 steps.
n = 6
rows, frames = run(os.path.join(work, "fields_2d"), f"mesh.n={n}", "time.T=0.02", "time.dt=0.001", "output.every=5")
assert sorted(frames) == [0, 5, 10, 15, 20], sorted(frames)
for step, m in frames.items():
    assert m.points.shape == ((n + 1) ** 2, 3) and np.all(m.points[:, 2] == 0.0)
    assert one_cell_block(m, "triangle").shape == (2 * n * n, 3)
    u, v, lam = (m.point_data[k].ravel() for k in ("u", "v", "lambda"))
    x, y = m.points[:, 0], m.points[:, 1]
    boundary = (x == 0) | (x == 1) | (y == 0) | (y == 1)
    assert np.all(u[boundary] == 0.02), u[boundary]
    assert np.all(lam <= 1e-10), lam.max()
    centre = np.flatnonzero((np.abs(x - 0.5) < 1e-12) & (np.abs(y - 0.5) < 1e-12))
    assert len(centre) == 1
    r = rows[step]
    for name, values in (("u", u), ("v", v), ("lambda", lam)):
        assert abs(values[centre[0]] - float(r[name + "@centre"])) <= 1e-12 * max(1.0, abs(values[centre[0]])), (
            step, name, values[centre[0]], r[name + "@centre"])
    if step == 0:
        assert np.all(u == 0.02) and np.all(v == 0.0) and np.all(lam == 0.0)
    else:
        assert np.any(u < 0.02) and np.any(v < 0.0)  # the membrane falls
print(f"2D: {len(frames)} files, {len(m.points)} points, u(centre, t = 0.02) = {u[centre[0]]:.6g}")

# 1D: a bar clamped on the right, obstacle on the left, VTK_LINE cells.
n = 8
rows, frames = run(os.path.join(work, "fields_1d"), "mesh.kind=interval", f"mesh.n={n}", "physics.model=bar",
                   "dirichlet.parts=right", "dirichlet.value=0", "obstacle.where=left", "initial.u=(1 - x)/2",
                   "physics.f=0", "output.probes={ tip = [0.0] }", "time.T=0.01", "time.dt=0.001", "output.every=10")
assert sorted(frames) == [0, 10], sorted(frames)
for step, m in frames.items():
    assert m.points.shape == (n + 1, 3) and np.all(m.points[:, 1:] == 0.0)
    assert one_cell_block(m, "line").shape == (n, 2)
    u = m.point_data["u"].ravel()
    assert u[np.argmax(m.points[:, 0])] == 0.0  # clamped
    assert u[np.argmin(m.points[:, 0])] == float(rows[step]["u@tip"])  # the tip is a vertex
print(f"1D: {len(frames)} files, {len(m.points)} points, line cells")

# gmsh: the L-shaped membrane, run from the work directory (not the scene's).
summary = subprocess.run([cdyn, "mesh", os.path.join(os.path.dirname(lshape), "..", "geo", "lshape.geo")],
                         check=True, stdout=subprocess.PIPE, text=True).stdout
n_vertices = int(re.search(r"vertices\s+(\d+)", summary).group(1))
rows, frames = run(os.path.join(work, "fields_lshape"), "time.T=0.01", scene=lshape, cwd=work)
m = frames[max(frames)]
assert m.points.shape == (n_vertices, 3), (m.points.shape, n_vertices)
x, y = m.points[:, 0], m.points[:, 1]
u = m.point_data["u"].ravel()
eps = 1e-12
outer = (x < eps) | (y < eps) | ((x > 1 - eps) & (y < 0.5 + eps)) | ((y > 1 - eps) & (x < 0.5 + eps))
reentrant = ~outer & (((np.abs(y - 0.5) < eps) & (x > 0.5)) | ((np.abs(x - 0.5) < eps) & (y > 0.5)))
assert np.all(u[outer] == 0.02) and reentrant.any() and np.all(u[reentrant] < 0.02)
print(f"lshape: {len(m.points)} points, u = 0.02 on {outer.sum()} outer points, free on {reentrant.sum()} re-entrant")
# An inclined plane: λ = λ_N n at the contact vertices, in (x, y).
ramp = os.path.join(os.path.dirname(lshape), "ramp.toml")
rows, frames = run(os.path.join(work, "fields_ramp"), "time.T=1e-3", "output.every=100", scene=ramp)
normal = np.array([-0.5, 0.8660254037844386])
lam = frames[100].point_data["lambda"][:, :2]
active = np.linalg.norm(lam, axis=1) > 1e-6 * np.abs(lam).max()
assert active.sum() >= 2, active.sum()
cross = np.abs(lam[active, 0] * normal[1] - lam[active, 1] * normal[0]) / np.linalg.norm(lam[active], axis=1)
assert cross.max() <= 1e-12, cross.max()
assert np.all(lam[active] @ normal < 0), lam[active] @ normal
print(f"ramp: {active.sum()} vertices in contact at step 100, max |λ × n|/|λ| = {cross.max():.1e}, λ·n < 0")

# Stress, strain and contact pressure of the same frame.
m = frames[100]
n_points, tri = len(m.points), one_cell_block(m, "triangle")
lam_, mu_ = 300.0, 150.0
cell = {k: m.cell_data[k][0] for k in ("sigma", "epsilon", "von_mises", "region")}
assert cell["sigma"].shape == (len(tri), 9) and cell["epsilon"].shape == (len(tri), 9), cell["sigma"].shape
assert m.point_data["sigma"].shape == (n_points, 9) and m.point_data["von_mises"].size == n_points
assert np.all(cell["region"] == 0)
sig, eps = cell["sigma"].reshape(-1, 3, 3), cell["epsilon"].reshape(-1, 3, 3)
assert np.all(sig == np.transpose(sig, (0, 2, 1))) and np.all(eps[:, 2, :] == 0) and np.all(eps[:, :, 2] == 0)
tr = eps[:, 0, 0] + eps[:, 1, 1]
law = lam_ * tr[:, None, None] * np.eye(3) + 2 * mu_ * eps
scale = np.abs(sig).max()
assert scale > 0 and np.abs(sig - law).max() <= 1e-12 * scale, np.abs(sig - law).max() / scale
dev = sig - np.trace(sig, axis1=1, axis2=2)[:, None, None] / 3 * np.eye(3)
vm = np.sqrt(1.5 * (dev * dev).sum(axis=(1, 2)))
assert np.abs(cell["von_mises"].ravel() - vm).max() <= 1e-12 * scale
# vertex values: the area-weighted averages of the cell values
p = m.points
area = 0.5 * np.abs((p[tri[:, 1], 0] - p[tri[:, 0], 0]) * (p[tri[:, 2], 1] - p[tri[:, 0], 1]) -
                    (p[tri[:, 2], 0] - p[tri[:, 0], 0]) * (p[tri[:, 1], 1] - p[tri[:, 0], 1]))
num, den = np.zeros((n_points, 9)), np.zeros(n_points)
for k in range(3):
    np.add.at(num, tri[:, k], area[:, None] * cell["sigma"])
    np.add.at(den, tri[:, k], area)
assert np.abs(m.point_data["sigma"] - num / den[:, None]).max() <= 1e-12 * scale
# contact pressure: contact.csv's at step 100, 0 elsewhere
pressure = m.point_data["contact_pressure"].ravel()
with open(os.path.join(work, "fields_ramp", "contact.csv")) as f:
    contact = {int(r["vertex"]): float(r["pressure"]) for r in csv.DictReader(f) if int(r["step"]) == 100}
others = np.setdiff1d(np.arange(n_points), list(contact))
assert np.all(pressure[others] == 0.0) and max(contact.values()) > 0
assert max(abs(pressure[v] - q) for v, q in contact.items()) <= 1e-12 * max(contact.values())
print(f"ramp: sigma = lambda tr(eps) I + 2 mu eps in {len(tri)} cells to {np.abs(sig - law).max() / scale:.1e}, "
      f"von Mises, vertex averages; contact_pressure at {len(contact)} vertices as contact.csv")
print("check_fields: ok")
