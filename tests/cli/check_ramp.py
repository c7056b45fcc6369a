#!/usr/bin/env python3
"""check_ramp.py — an obstacle whose normal is not a coordinate axis, through the
command line: the disk of data/scenes/ramp.toml thrown at a plane inclined by 30°
(docs/elasticity.md §7, docs/experiments.md).

Usage: check_ramp.py CDYN SOURCE_DIR WORKDIR

  - Frictionless contact pushes along n only, Gᵀλ ∥ n vertex by vertex, so the momentum
    along the plane, P·t (t = (cos 30°, sin 30°)), changes by gravity alone: P·t =
    m (v0·t + (g·t) t) at every step, in contact or not (v0·t = 0 here), with
    m = ρ|Ω_h|.  The translation is in W^h and in ker K, and the midpoint rule
    integrates a constant force exactly, so the momentum is off only by what the step
    solves leave: pdas's CG stops at half the QP tolerance on the natural residual,
    which acts as a force of that size.  Over the 600 contact steps it adds up to
    ≈ 1e-10 of m|v0| at the scene's solver.tol = 1e-10 and 6e-12 at 1e-12, so both
    runs here use 1e-12 and the identity is asserted to 1e-10 of m|v0|.
  - Rotation invariance: the same mesh turned back by −30° (its .msh nodes rotated,
    connectivity unchanged) against the horizontal plane, with gravity and v0 turned
    with it, is the same discrete problem in rotated coordinates, so its J, active set
    and contact force equal the ramp's at every step and its momentum is the ramp's
    turned by −30°.  The two runs differ only in the rounding of rotated coordinates
    (relative 1e-16 on 20 mm): asserted to 1e-8 (the kernel's rotation test,
    test_elastic_contact, measures 7e-13 on a small mesh; the 1000 steps here, 600 in
    contact, each solving S with condition number ~1e5 at most, stay far below 1e-8).
  - The probes' v (the rate over the last step) is the difference quotient of their u,
    in (x, y) also at the contact nodes, whose unknowns are rotated components.
  - No penetration along the inclined normal: with the constraint at the end of the
    step (backward Euler) the gaps (a + u(a) − p)·n of contact.csv are ≥ −1e-12 mm
    (round-off of 20 mm coordinates) and pdas ends with violation exactly 0.
"""
import math
import os
import subprocess
import sys

from cli_helpers import area, check, failures, run

cdyn, src, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
theta = math.radians(30.0)
n = (-math.sin(theta), math.cos(theta))
t = (math.cos(theta), math.sin(theta))
rho, v0, g = 1e-6, 1000.0, 9810.0

# The ramp's mesh as a .msh (MSH 2.2: one node per line, "id x y z"), and the same
# nodes turned by −θ about the origin, the plane's point.
geo = os.path.join(src, "data", "geo", "ramp.geo")
ramp_msh, flat_msh = os.path.join(work, "ramp.msh"), os.path.join(work, "flat.msh")
subprocess.run(["gmsh", "-2", geo, "-format", "msh22", "-o", ramp_msh], check=True, stdout=subprocess.DEVNULL)
with open(ramp_msh) as f:
    lines = f.read().split("\n")
begin = lines.index("$Nodes")
count = int(lines[begin + 1])
c, s_ = math.cos(-theta), math.sin(-theta)
for k in range(begin + 2, begin + 2 + count):
    i, x, y, z = lines[k].split()
    x, y = float(x), float(y)
    lines[k] = f"{i} {c * x - s_ * y!r} {s_ * x + c * y!r} {z}"
with open(flat_msh, "w") as f:
    f.write("\n".join(lines))

scene = os.path.join(src, "data", "scenes", "ramp.toml")
tight = "solver.tol=1e-12"  # (the momentum identity above)
ramp, h_ramp, _ = run(cdyn, scene, os.path.join(work, "ramp"), f"mesh.file={ramp_msh}", tight)
flat_sets = [f"mesh.file={flat_msh}", tight, "obstacle.normal=[0.0, 1.0]",
             f"physics.gravity=[{-g * math.sin(theta)!r}, {-g * math.cos(theta)!r}]",
             'initial.v=["0", "-1000"]', "output.probes={}"]
flat, h_flat, _ = run(cdyn, scene, os.path.join(work, "flat"), *flat_sets)

m = rho * area(cdyn, ramp_msh)
g_t = -g * t[1]  # g·t with g = (0, −g)
err_t = max(abs(r["px"] * t[0] + r["py"] * t[1] - m * g_t * r["t"]) for r in h_ramp) / (m * v0)
impact = ramp["impact"]
check(impact["contact"] and impact["after"] is not None and err_t < 1e-10,
      f"ramp: momentum along the plane = m (g.t) t to {err_t:.1e} of m v0, through "
      f"{impact['contact_steps']} contact steps")
P_n = impact["after"]["momentum"][0] * n[0] + impact["after"]["momentum"][1] * n[1]
check(P_n > 0, f"ramp: the disk leaves the plane (P.n after = {P_n:.4g} N s/mm)")

scale_E, scale_F = ramp["E0"], impact["peak_force"]
err_E = max(abs(a["E_total"] - b["E_total"]) for a, b in zip(h_ramp, h_flat)) / scale_E
err_F = max(abs(a["contact_force"] - b["contact_force"]) for a, b in zip(h_ramp, h_flat)) / scale_F
same_active = all(a["active"] == b["active"] for a, b in zip(h_ramp, h_flat))
err_P = max(math.hypot(c * a["px"] - s_ * a["py"] - b["px"], s_ * a["px"] + c * a["py"] - b["py"])
            for a, b in zip(h_ramp, h_flat)) / (m * v0)
check(len(h_ramp) == len(h_flat) and same_active and max(err_E, err_F, err_P) < 1e-8,
      f"ramp = flat plane turned by 30 deg: J to {err_E:.1e}, contact force to {err_F:.1e}, "
      f"momentum to {err_P:.1e}, same active sets")

# The probes' v is the displacement rate over the last step, in (x, y), so it is the
# difference quotient of their u columns: an identity up to the rounding of u
# (|u| ≤ 20 mm, ε|u|/dt ≈ 4e-10 mm/s; asserted to 1e-6 mm/s against |v| ~ 1e3).  The
# probe "nearest" sits on the contact nodes, whose unknowns are the rotated (n, t)
# components: before the rate was turned back with global(), its v was off by up to
# 1.5e3 mm/s there.
dt = 1e-5
err_v = max(abs((b[f"u{c}@{pr}"] - a[f"u{c}@{pr}"]) / dt - b[f"v{c}@{pr}"])
            for a, b in zip(h_ramp, h_ramp[1:]) for c in "xy" for pr in ("nearest", "centre"))
check(err_v < 1e-6, f"ramp: probe v = (u^n - u^(n-1))/dt in (x, y) to {err_v:.1e} mm/s")

be, _, contact = run(cdyn, scene, os.path.join(work, "ramp_be"), f"mesh.file={ramp_msh}",
                     "time.scheme=backward_euler", "output.contact_every=1")
min_gap = min(r["gap"] for r in contact)
check(be["max_violation"] == 0 and min_gap >= -1e-12,
      f"ramp, backward Euler: no penetration along n (min gap {min_gap:.1e} mm)")

if failures:
    sys.exit("FAIL: " + "; ".join(failures))
print("ramp checks passed")
