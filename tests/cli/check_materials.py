#!/usr/bin/env python3
"""check_materials.py — materials by region, the stress fields and the .geo parameters
from the command line (docs/scenes.md, docs/outputs.md, docs/elasticity.md).

Usage: check_materials.py CDYN SOURCE_DIR WORKDIR

data/scenes/two_layer.toml: a 10 x 20 mm column, a soft layer under a stiff one
(regions "soft", "stiff" of data/geo/two_layer.geo), sides on rollers, the top pressed
by p = 1 N/mm^2, resting on the plane y = 0; quasi-static backward Euler.  The static
solution is one-dimensional (an oedometer): two springs in series,
    u_y(top) = -p (h_soft / M_soft + h_stiff / M_stiff),  M = E(1 - nu)/((1 + nu)(1 - 2 nu)),
sigma_yy = -p in both layers, sigma_xx = sigma_zz = -p lambda_r / M_r (a jump at the
interface).  P1+ contains it; what is left after 5 steps of dt = 0.1 s is the inertia
term M/dt^2 (measured 3e-13 relative); asserted 1e-9:
  - the last field file (meshio): u_y at the top vertices, the cell data "sigma" per
    region (told apart by the cell data "region"), "von_mises" of each cell's sigma,
    the point data "contact_pressure" = p at the vertices of the base (= contact.csv's
    pressure) and 0 elsewhere, the point "sigma" away from the interface;
  - the same with --set mesh.set.h=2 and 0.5: more vertices for a smaller h, the same
    answer (the solution is in the space whatever the triangulation);
  - free flight (no obstacle, no load, gravity g, midpoint): the momentum is
    -(rho_soft |soft| + rho_stiff |stiff|) g t, to 1e-10 relative: the per-region density
    enters the mass and the weight alike;
  - one material given per region with the body's own values is the single-material
    run bit for bit (data/scenes/disk.toml and its region "disk");
  - `cdyn study --vary mesh.set.h=2,1`: two runs, the dofs grow;
  - output.stress = false writes no stress arrays (and keeps the others).
Exit status 77 (skipped) when meshio or numpy is missing.
"""
import csv
import glob
import os
import shutil
import subprocess
import sys

from cli_helpers import import_meshio, run as run_scene

meshio, np = import_meshio("check_materials")
cdyn, source, work = sys.argv[1], sys.argv[2], sys.argv[3]
scene = os.path.join(source, "data", "scenes", "two_layer.toml")
disk = os.path.join(source, "data", "scenes", "disk.toml")

P = 1.0
SOFT = dict(E=100.0, nu=0.45, rho=1.2e-6)
STIFF = dict(E=2000.0, nu=0.3, rho=1e-6)


def lame(m):
    E, nu = m["E"], m["nu"]
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def oedometric(m):
    lam, mu = lame(m)
    return lam + 2 * mu


U_TOP = -P * (10.0 / oedometric(SOFT) + 10.0 / oedometric(STIFF))


def run(out, *sets, scene_file=scene):
    """`cdyn run` with its field files (cli_helpers.run turns them off): (summary, history rows)."""
    summary, rows, _ = run_scene(cdyn, scene_file, out, "output.fields=true", *sets)
    return summary, rows


def last_frame(out):
    return meshio.read(sorted(glob.glob(os.path.join(out, "fields", "step_*.vtu")))[-1])


def check_oedometer(out, label):
    m = last_frame(out)
    x, y = m.points[:, 0], m.points[:, 1]
    uy = m.point_data["u"][:, 1]
    top, base = np.isclose(y, 20.0), np.isclose(y, 0.0)
    err_u = np.abs(uy[top] - U_TOP).max() / abs(U_TOP)
    assert err_u <= 1e-9, (label, err_u)
    # cell data, one block of triangles
    region = m.cell_data["region"][0].ravel().astype(int)
    sigma = m.cell_data["sigma"][0].reshape(-1, 3, 3)
    vm = m.cell_data["von_mises"][0].ravel()
    tri = m.cells[0].data
    yc = y[tri].mean(axis=1)
    assert np.all((region == 0) == (yc < 10.0)), label  # region 0 is "soft", below y = 10
    err_s = 0.0
    for r, mat in ((0, SOFT), (1, STIFF)):
        lam, mu = lame(mat)
        side = -P * lam / (lam + 2 * mu)
        s = sigma[region == r]
        expected = np.array([[side, 0, 0], [0, -P, 0], [0, 0, side]])
        err_s = max(err_s, np.abs(s - expected).max() / P)
        vm_expected = abs(side + P)  # sigma_xx = sigma_zz: von Mises = |sigma_yy - sigma_xx|
        err_s = max(err_s, np.abs(vm[region == r] - vm_expected).max() / P)
    assert err_s <= 1e-9, (label, err_s)
    # the vertex values away from the interface are those of their layer's cells
    point_sigma = m.point_data["sigma"].reshape(-1, 3, 3)
    away = ~np.isclose(y, 10.0)
    assert np.abs(point_sigma[away, 1, 1] + P).max() <= 1e-9 * P, label
    # contact pressure: p at the base, 0 elsewhere (as contact.csv's last rows)
    pressure = m.point_data["contact_pressure"].ravel()
    assert np.abs(pressure[base] - P).max() <= 1e-9 * P, (label, pressure[base])
    assert np.all(pressure[~base] == 0.0), label
    with open(os.path.join(out, "contact.csv")) as f:
        rows = list(csv.DictReader(f))
    last = max(int(r["step"]) for r in rows)
    for r in rows:
        if int(r["step"]) == last:
            v = int(r["vertex"])
            assert abs(pressure[v] - float(r["pressure"])) <= 1e-12 * P, (label, v)
    return len(m.points), err_u, err_s


run(os.path.join(work, "two_layer"))
n1, err_u, err_s = check_oedometer(os.path.join(work, "two_layer"), "h = 1")
print(f"two_layer (h = 1, {n1} vertices): u_y(top) = {U_TOP:.8f} mm to {err_u:.1e}, sigma and von Mises per region to "
      f"{err_s:.1e}, contact pressure p at the base")

# output.stress = false: no stress arrays, the rest as before.
out = os.path.join(work, "two_layer_no_stress")
run(out, "output.stress=false")
m = last_frame(out)
assert not {"sigma", "epsilon", "von_mises"} & (set(m.point_data) | set(m.cell_data)), (m.point_data.keys(), m.cell_data.keys())
assert "contact_pressure" in m.point_data and "region" in m.cell_data
size = lambda d: os.path.getsize(sorted(glob.glob(os.path.join(d, "fields", "step_*.vtu")))[-1])
print(f"output.stress = false: no sigma, epsilon, von_mises; {size(out)} bytes a file instead of "
      f"{size(os.path.join(work, 'two_layer'))}")

# Refinement through the .geo's parameter: more vertices, the same answer.
counts = {}
for h in ("2", "0.5"):
    out = os.path.join(work, f"two_layer_h{h}")
    summary, _ = run(out, f"mesh.set.h={h}")
    counts[h], e_u, e_s = check_oedometer(out, f"h = {h}")
assert counts["2"] < n1 < counts["0.5"], counts
print(f"mesh.set.h = 2, 1, 0.5: {counts['2']}, {n1}, {counts['0.5']} vertices, the same answer")

# Free flight: the momentum of the two densities under gravity.
g = 9810.0
summary, rows = run(os.path.join(work, "two_layer_flight"), "obstacle.enabled=false", "neumann.traction=[0, 0]",
                    f"physics.gravity=[0, -{g}]", "time.scheme=midpoint", "time.dt=1e-5", "time.T=2e-4",
                    "output.fields=false")
mass = 100.0 * SOFT["rho"] + 100.0 * STIFF["rho"]
err_p = max(abs(r["py"] + mass * g * r["t"]) for r in rows) / (mass * g * rows[-1]["t"])
assert err_p <= 1e-10, err_p
assert max(abs(r["px"]) for r in rows) <= 1e-10 * mass * g * rows[-1]["t"]  # nothing pushes along x
print(f"free flight: p_y = -(rho_soft |soft| + rho_stiff |stiff|) g t to {err_p:.1e}")

# One material given per region, equal to the body's: the single-material run, bit for bit.
plain = os.path.join(work, "disk_plain")
same = os.path.join(work, "disk_region")
common = ["time.T=2e-4", "output.fields=false"]
run(plain, *common, scene_file=disk)
run(same, *common, "materials.disk.lambda=300", "materials.disk.mu=150", "materials.disk.rho=1e-6", scene_file=disk)


def columns(out):
    with open(os.path.join(out, "history.csv")) as f:
        return [{k: v for k, v in r.items() if k not in ("solve_s", "step_s", "reconstruction_s")} for r in csv.DictReader(f)]


assert columns(plain) == columns(same)
print(f"disk with [materials.disk] = physics: history.csv identical ({len(columns(plain))} rows)")

# A refinement study over the .geo parameter.
out = os.path.join(work, "two_layer_study")
shutil.rmtree(out, ignore_errors=True)
subprocess.run([cdyn, "study", scene, "--out", out, "--vary", "mesh.set.h=2,1", "--set", "time.T=0.2"], check=True,
               stdout=subprocess.DEVNULL)
with open(os.path.join(out, "study.csv")) as f:
    study = list(csv.DictReader(f))
assert len(study) == 2 and int(study[0]["n_dofs"]) < int(study[1]["n_dofs"]), study
print(f"cdyn study --vary mesh.set.h=2,1: n_dofs {study[0]['n_dofs']} -> {study[1]['n_dofs']}")
print("check_materials: ok")
