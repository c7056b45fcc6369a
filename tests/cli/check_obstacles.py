#!/usr/bin/env python3
"""check_obstacles.py — rigid obstacles of any shape, that move, several of them, and the
penetration of the whole boundary (docs/scenes.md, "Obstacles"), against the numbers
their mechanics fixes.

Usage: check_obstacles.py CDYN SOURCE_DIR WORKDIR

- A curved obstacle (data/scenes/hertz_cylinder.toml: the half cylinder R₁ = 20 mm on a
  rigid cylinder R₂ = 20 mm through obstacle.gap): at the end of the loading the nodal
  forces, each along its vertex's normal, add up to P = 160 N/mm along y (static
  equilibrium, as for hertz.toml, to 1e-6 P; measured 5e-11) and nothing along x;
  Hertz's half-width for two cylinders, a = √(4PR(1 − ν²)/(πE)) with R = R₁R₂/(R₁ + R₂),
  lies between the last vertex in contact and the next on each side; the nodal pressures
  inside the zone follow p(x) = (2P/(πa²))√(a² − x²) to 3 % of its peak (measured 2.5 %
  with the vertex next to the edge, where the P1 trace samples the √ singularity of the
  slope; the plane of hertz.toml gets 0.7 % with twice the zone); the contact opens after
  the release.
- The plane written as a gap function, obstacle.gap = "y", gives the contact forces of
  the plane (point, normal) of hertz.toml to 1e-8 P (the normals of a linear gap by
  central differences are exact to round-off).
- A moving obstacle (data/scenes/pushed_block.toml: a plane pushing a unit block at
  speed w = 0.1 from rest, ν = 0, c = 1): the contact lasts 2L/c = 2 (the last contact
  step at t = 2 exactly: the wave's return is resolved to a step), the impulse is the
  block's momentum after it (the impact summary's identity, to 1e-10) and is 2ρLw = 0.2
  within 3 % (measured 0.19543: 2.3 % at n = 16, dt = 1/64, the P1+/P0 error of the
  discontinuous wave front; 0.56 % for the 1D bar of tests/unit/test_moving_obstacle.cpp),
  as is the momentum after, with no violation; discrete_gradient balances J against the data's work W to 1e-9 of
  E_scale (measured 1.8e-11) while midpoint's J − J0 − W stays below 5e-3 E_scale
  (measured 1.0e-3).
- Two obstacles (data/scenes/two_obstacles.toml, a floor and a wall): the momentum the
  block gains is the impulse of each obstacle, Δp_x = −Σ F_wall dt and
  Δp_y = Σ F_floor dt from contact.csv (an identity of the midpoint scheme, measured
  2e-11), and both obstacles act; the corner vertex (1, 0) is held by the floor only (the
  nearer at t = 0) and the wall lets it through: max_penetration > 0 = max_violation, and
  the run warns.
- obstacle.where = "top" on a block falling onto a plane: the bottom goes through
  unchecked; the penetration column sees it (T = 0.5 at v = 0.5 from a gap of 0.05: depth
  0.2 exactly, to 1e-12) and the run warns.
- The disk with where = "boundary" (every boundary vertex constrained) moves as with
  where = "contact" when only Γ_C touches: the same energies and momenta (bit for bit),
  the contact force to the QP's round-off.
Only the standard library is used.
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

from cli_helpers import check, check_hertz_zone, failures, hertz_pressure_deviation, read_csv

cdyn, src, work = sys.argv[1:4]
scenes = os.path.join(src, "data", "scenes")
os.makedirs(work, exist_ok=True)


def run(scene, out, *sets):
    """(summary, history rows, contact rows, stderr) of `cdyn run` without fields and plots."""
    out = os.path.join(work, out)
    shutil.rmtree(out, ignore_errors=True)
    args = [cdyn, "run", os.path.join(scenes, scene), "--out", out, "--quiet",
            "--set", "output.fields=false", "--set", "output.plots=false", "--set", "output.contact_every=1"]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, check=True, stderr=subprocess.PIPE, text=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    contact = os.path.join(out, "contact.csv")
    return summary, read_csv(os.path.join(out, "history.csv")), read_csv(contact), p.stderr


def rows_at(contact, step):
    return sorted((r for r in contact if int(r["step"]) == step), key=lambda r: r["x"])


# --- a curved obstacle: Hertz for two cylinders ----------------------------------------
s, h, c, _ = run("hertz_cylinder.toml", "hertz_cylinder")
E, nu, R1, R2, P = 400.0, 1.0 / 3.0, 20.0, 20.0, 160.0
R = R1 * R2 / (R1 + R2)
a = math.sqrt(4 * P * R * (1 - nu * nu) / (math.pi * E))
loaded = rows_at(c, 5)
# The force of each vertex acts along its own normal n(a) = (a − c)/|a − c| (c the
# rigid cylinder's centre): the resultant's y component balances P, its x component
# vanishes by symmetry.
centre = (0.0, -R2)
normals = [((r["x"] - centre[0]) / math.hypot(r["x"] - centre[0], r["y"] - centre[1]),
            (r["y"] - centre[1]) / math.hypot(r["x"] - centre[0], r["y"] - centre[1])) for r in loaded]
fx = sum(r["force"] * n[0] for r, n in zip(loaded, normals))
fy = sum(r["force"] * n[1] for r, n in zip(loaded, normals))
check(abs(fy - P) < 1e-6 * P and abs(fx) < 1e-6 * P, f"cylinder: resultant ({fx:.2e}, {fy:.9g}) = (0, P = {P})")
check_hertz_zone("cylinder", loaded, a, P)
interior = [r for r in loaded if abs(r["x"]) < a]
dev, p0 = hertz_pressure_deviation(interior, a, P)
check(len(interior) >= 9 and dev < 0.03,
      f"cylinder: pressure = Hertz's to {dev:.1%} of p0 = {p0:.4g} N/mm² at {len(interior)} vertices")
released = rows_at(c, int(h[-1]["step"]))
check(all(abs(r["force"]) < 1e-9 * P for r in released) and min(r["gap"] for r in released) > 0,
      "cylinder: the contact opens after the release")

# --- the plane as a gap function --------------------------------------------------------
_, _, plane, _ = run("hertz.toml", "hertz_plane")
_, _, gap, _ = run("hertz_cylinder.toml", "hertz_gap_y", "obstacle.gap=y")
worst = max(abs(p["force"] - g["force"]) for p, g in zip(plane, gap))
check(len(plane) == len(gap) and worst < 1e-8 * P, f"gap = \"y\": the plane's contact forces to {worst / P:.1e} P")

# --- a moving obstacle: the pushed block ------------------------------------------------
w, L, rho, c_p = 0.1, 1.0, 1.0, 1.0
for scheme, bound in (("midpoint", 5e-3), ("discrete_gradient", 1e-9)):
    s, h, _, _ = run("pushed_block.toml", "pushed_" + scheme, "time.scheme=" + scheme)
    imp = s["impact"]
    I, after = imp["impulse"], imp["after"]["momentum"][1]
    check(abs(I / (2 * rho * L * w) - 1) < 0.03 and abs(after / (2 * rho * L * w) - 1) < 0.03 and s["max_violation"] == 0,
          f"pushed block, {scheme}: impulse {I:.6f}, momentum after {after:.6f} = 2ρLw = 0.2 to "
          f"{abs(after / 0.2 - 1):.1%}, no violation")
    check(imp["t_last_contact"] == 2 * L / c_p, f"pushed block, {scheme}: last contact at t = {imp['t_last_contact']} = 2L/c")
    W = h[-1]["data_work"]
    check(abs(s["data_work"] - W) < 1e-15 and s["E_rel_drift"] < bound,
          f"pushed block, {scheme}: |J - J0 - W| = {s['E_rel_drift']:.1e} E_scale (< {bound:g}), W = {W:.6g}")
    # Midpoint's momentum changes by the contact impulse alone (an identity of the
    # scheme); discrete_gradient's correction β M (U^{n+1} − Uⁿ) of the switching steps is
    # a force too (measured 5e-5 of the momentum here).
    if scheme == "midpoint":
        check(abs(I - after) < 1e-10, f"pushed block, midpoint: impulse = momentum after to {abs(I - after):.1e}")
# --- two obstacles ------------------------------------------------------------------------
s, h, c, stderr = run("two_obstacles.toml", "two_obstacles")
dt = s["dt"]
floor = sum(r["force"] for r in c if int(r["step"]) > 0 and abs(r["y"]) < 1e-12) * dt
wall = sum(r["force"] for r in c if int(r["step"]) > 0 and abs(r["x"] - 1) < 1e-12 and r["y"] > 1e-12) * dt
dpx, dpy = h[-1]["px"] - h[0]["px"], h[-1]["py"] - h[0]["py"]
check(floor > 0.1 and wall > 0.1 and abs(dpy - floor) < 1e-9 and abs(dpx + wall) < 1e-9,
      f"two obstacles: Δp = ({dpx:.6f}, {dpy:.6f}) = (−wall, floor) impulses ({wall:.6f}, {floor:.6f})")
check(s["max_violation"] == 0 and s["max_penetration"] > 0.01 and any("max_penetration" in x for x in s["warnings"])
      and "cdyn: warning: the boundary went" in stderr,
      f"two obstacles: the corner vertex, held by the floor, goes {s['max_penetration']:.3g} into the wall; warned")

# --- a part not in `where` passes through -----------------------------------------------
top_only = os.path.join(work, "top_only.toml")
with open(top_only, "w") as f:
    f.write("""name = "top_only"
[mesh]
kind = "unit_square"
n = 4
[physics]
model = "elasticity"
E = 1.0
nu = 0.3
[obstacle]
where = "top"
point = [0.0, -0.05]
[initial]
v = ["0", "-0.5"]
[time]
dt = 0.01
T = 0.5
""")
s, h, _, stderr = run(top_only, "top_only")
depth = 0.5 * 0.5 - 0.05
check(abs(s["max_penetration"] - depth) < 1e-12 and abs(h[-1]["penetration"] - depth) < 1e-12 and s["max_violation"] == 0
      and "cdyn: warning: the boundary went" in stderr,
      f"where = top: the bottom goes {s['max_penetration']:.12g} = {depth} into the plane, seen and warned")

# --- where = "boundary" -------------------------------------------------------------------
_, hc, _, _ = run("disk.toml", "disk_contact", "time.T=0.004")
_, hb, _, _ = run("disk.toml", "disk_boundary", "time.T=0.004", "obstacle.where=boundary")
# Energies and momenta bit for bit (measured); the contact force sums the reactions of
# every constrained vertex, the round-off of the inactive ones too (the QP's tolerance:
# measured 3.5e-9 of the peak force), asserted 1e-8.
def largest_difference(k):
    return max(abs(x[k] - y[k]) for x, y in zip(hc, hb)) / max(1e-300, max(abs(x[k]) for x in hc))
exact = max(largest_difference(k) for k in ["E_kin", "E_pot", "E_total", "px", "py", "penetration"])
force = largest_difference("contact_force")
check(len(hc) == len(hb) and exact < 1e-12 and force < 1e-8,
      f"disk, where = boundary: the run of where = contact (energies, momenta to {exact:.1e}, force to {force:.1e})")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
