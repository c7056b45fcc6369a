#!/usr/bin/env python3
"""check_membrane_3d.py — the scalar obstacle problem on the unit cube
(data/scenes/membrane_3d.toml) through `cdyn run`, on a 4 × 4 × 4 cube for T = 0.4
(200 steps of dt = 0.002):

  - every pair and classical mass runs with its recommended scheme (time.scheme =
    auto: discrete_gradient or midpoint_end, which constrain the full steps; the
    redistributed mass with a contact face: Γ_D the top face, the obstacle on the bottom
    face), touches the obstacle, stays feasible (max_violation at the QP's tolerance)
    and reports condition (12) as test_wellposedness_3d finds it (P1+/P0, P1+/P1, P2/P1
    satisfied; P1/P1, P1/P0 and the classical masses not; the redistributed mass with
    Γ_C a face: satisfied);
  - every scheme runs with a mass model it accepts (paoli_schatzman and
    energy_conserving need an invertible M: the lumped mass);
  - the four step solvers give the same run: J(T) within 1e-9 relative of pdas's
    (pgs, ipopt and nlopt stop at their own tolerances; measured ≤ 2.2e-12);
  - without the obstacle the midpoint rule conserves J to round-off (measured
    8.6e-13 over the 200 steps; bound 5e-12 — the unit tests' 1e-12 is over a coarser
    cube);
  - the field files hold the tetrahedra (VTK type 10, 6n³ cells, (n+1)³ points with
    their z), u = 0.02 on the boundary and u ≥ g at the vertices (python3-meshio;
    skipped without it).

Usage: check_membrane_3d.py CDYN SOURCE_DIR WORKDIR
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import check, failures, run  # noqa: E402

cdyn, src, work = sys.argv[1:4]
scene = os.path.join(src, "data", "scenes", "membrane_3d.toml")
small = ["mesh.n=4", "time.T=0.4"]


def out(name):
    return os.path.join(work, name)


# Every pair and classical mass, with the recommended scheme and pdas.
expected_12 = {"P1/P1": False, "P1/P0": False, "P1+/P0": True, "P1+/P1": True, "P2/P1": True,
               "consistent": False, "lumped": False}
for pair, satisfied in expected_12.items():
    key = "method.mass" if pair in ("consistent", "lumped") else "method.pair"
    s, history, _ = run(cdyn, scene, out(pair.replace("/", "_").replace("+", "b")), *small, f"{key}={pair}",
                        "time.scheme=auto")
    active = max(r["active"] for r in history)
    check(active > 0, f"{pair}: the field reaches the obstacle ({int(active)} constraints active at most)")
    check(s["max_violation"] <= 1e-10, f"{pair}: max_violation {s['max_violation']:.1e} <= 1e-10")
    check(s["wellposed"]["satisfied"] == satisfied,
          f"{pair}: condition (12) {'satisfied' if satisfied else 'violated'} (beta = {s['wellposed']['beta']})")
s, history, _ = run(cdyn, scene, out("redistributed"), *small, "method.mass=redistributed", "dirichlet.parts=[\"top\"]",
                    "obstacle.where=[\"bottom\"]", "time.scheme=auto")
check(max(r["active"] for r in history) > 0 and s["max_violation"] <= 1e-10,
      f"redistributed (contact on the bottom face): in contact, max_violation {s['max_violation']:.1e}")
check(s["wellposed"]["satisfied"] is True, f"redistributed: condition (12) satisfied (beta = {s['wellposed']['beta']})")

# Every scheme.
for scheme, mass in (("backward_euler", "method.pair=P1+/P0"), ("midpoint", "method.pair=P1+/P0"),
                     ("midpoint_end", "method.pair=P1+/P0"), ("newmark", "method.pair=P1+/P0"),
                     ("discrete_gradient", "method.pair=P1+/P0"), ("paoli_schatzman", "method.mass=lumped"),
                     ("energy_conserving", "method.mass=lumped")):
    s, history, _ = run(cdyn, scene, out("scheme_" + scheme), *small, mass, f"time.scheme={scheme}")
    check(s["scheme"] == scheme and s["n_steps"] == 200 and max(r["active"] for r in history) > 0,
          f"{scheme}: 200 steps, in contact, J(T)/J0 = {s['E_final'] / s['E0']:.6f}")

# Every step solver, the same run.
reference = None
for solver in ("pdas", "pgs", "ipopt", "nlopt"):
    s, _, _ = run(cdyn, scene, out("solver_" + solver), *small, f"solver.name={solver}", "time.scheme=midpoint")
    reference = reference or s["E_final"]
    diff = abs(s["E_final"] - reference) / abs(reference)
    check(diff <= 1e-9, f"{solver}: J(T) {s['E_final']:.12f}, {diff:.1e} from pdas's")

# Energy without contact.
s, _, _ = run(cdyn, scene, out("no_obstacle"), *small, "obstacle.enabled=false", "time.scheme=midpoint")
check(s["E_rel_drift"] <= 5e-12, f"midpoint without the obstacle: max |J - J0|/|J0| = {s['E_rel_drift']:.1e} <= 5e-12")

# The field files.
try:
    import meshio
    import numpy as np
except ImportError:
    meshio = None
if meshio is None:
    print("fields: skipped (python3-meshio or numpy missing)")
else:
    import subprocess
    d = out("fields")
    subprocess.run([cdyn, "run", scene, "--out", d, "--quiet", "--set", "output.plots=false", "--set", "mesh.n=4",
                    "--set", "time.T=0.02"], check=True)
    m = meshio.read(os.path.join(d, "fields", "step_000000.vtu"))
    n = 4
    check([c.type for c in m.cells] == ["tetra"] and len(m.cells[0].data) == 6 * n ** 3,
          f"fields: {len(m.cells[0].data)} tetrahedra (6n^3 = {6 * n ** 3})")
    p = m.points
    check(p.shape == ((n + 1) ** 3, 3) and p[:, 2].min() == 0.0 and p[:, 2].max() == 1.0,
          f"fields: {p.shape[0]} points with z in [{p[:, 2].min()}, {p[:, 2].max()}]")
    on_boundary = np.any((p == 0.0) | (p == 1.0), axis=1)
    u = m.point_data["u"]
    check(np.all(u[on_boundary] == 0.02), "fields: u = 0.02 on the boundary")
    for f in sorted(os.listdir(os.path.join(d, "fields"))):
        m = meshio.read(os.path.join(d, "fields", f))
        gap = m.point_data["u"] - (0.01 - 0.04 * m.points[:, 2])
        check(gap.min() >= -1e-10, f"fields: {f}: u >= g at the vertices (min u - g = {gap.min():.2e})")

if failures:
    sys.exit("FAIL: " + ", ".join(failures))
