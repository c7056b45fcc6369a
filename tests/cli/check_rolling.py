#!/usr/bin/env python3
"""check_rolling.py — an elastic disk on an inclined plane with Coulomb friction: it rolls
without slipping when μ is large, and slides otherwise (docs/friction.md, "Rolling").

Usage: check_rolling.py CDYN SOURCE_DIR WORKDIR

data/scenes/disk.toml (radius 20 mm, plane strain, P1+/P0) released at rest on the plane,
the gravity turned by θ = 30° (the plane's frame), backward Euler, dt = 25 µs, T = 5 ms,
the material stiffened 100 times (λ = 30 000, μ = 15 000 N/mm²) towards the rigid disk.
The rigid-body values, as ratios of linear momenta at T to the frictionless slide (whose
P_x = m g sin θ t: no mass to compute):
  - μ = 1 (≥ tan θ / 3 = 0.19: no slip): a solid cylinder rolls with (2/3) g sin θ,
    ratio 2/3 — measured +0.21 % (lc = 2.5 mm) and +0.04 % (lc = 1.25 mm): the elastic
    release's transient; asserted 0.5 %;
  - μ = 0.1: it slides with g (sin θ − μ cos θ), ratio 1 − μ cot θ, over T = 20 ms
    (dt = 100 µs, lc = 2.5 mm) once the release's transient of the normal force has
    died out (at T = 5 ms it is still +0.35 %) — measured 2.5e-9, asserted 1e-6 (the
    stiffening: 2.0 % with the disk's own material, 0.09 % with 10 times it).
The window is short on purpose: the model is linear elasticity, whose displacement of a
rotation by φ is the tangent one, φ (−y, x); the disk's front then meets the plane at
an angle 2φ ahead of its lowest point, a spurious rolling resistance that grows with φ
and that a mesh with a vertex there feels (measured: −15 % at T = 50 ms, φ = 0.2 rad).
At T = 5 ms, φ = 2e-3 rad and 2φR = 0.08 mm, below the mesh's spacing.
Only the standard library is used.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import check, failures, run  # noqa: E402

cdyn, src, work = sys.argv[1:4]
scene = os.path.join(src, "data/scenes/disk.toml")
theta = math.radians(30.0)
g = 9810.0
COMMON = [f"physics.gravity=[{g * math.sin(theta)!r}, {-g * math.cos(theta)!r}]", "obstacle.point=[0.0, 0.5]",
          'initial.v=["0", "0"]', "time.scheme=backward_euler", "time.dt=2.5e-5", "time.T=0.005",
          "physics.lambda=30000", "physics.mu=15000"]


def momentum(name, *sets):
    _, rows, _ = run(cdyn, scene, os.path.join(work, name), *COMMON, *sets)
    return rows[-1]["px"]


for lc in ("2.5", "1.25"):
    free = momentum("free" + lc, "mesh.set.lc=" + lc)
    roll = momentum("roll" + lc, "mesh.set.lc=" + lc, 'contact.friction="coulomb"', 'contact.mu="1.0"')
    ratio = roll / free
    print(f"lc = {lc} mm: rolling P_x / frictionless P_x = {ratio:.6f} (2/3: {ratio / (2 / 3) - 1:+.2e})")
    check(abs(ratio / (2.0 / 3.0) - 1.0) <= 5e-3, f"lc = {lc}: the disk rolls without slipping, a = (2/3) g sin θ")

# Sliding, over 20 ms (dt = 100 µs): the release's transient has died out.
mu, longer = 0.1, ["time.T=0.02", "time.dt=1e-4"]
free = momentum("free-long", *longer)
slide = momentum("slide", *longer, 'contact.friction="coulomb"', f'contact.mu="{mu}"')
expected = 1.0 - mu / math.tan(theta)
print(f"sliding (μ = {mu}): P_x / frictionless P_x = {slide / free:.10f} (1 − μ cot θ = {expected:.10f})")
check(abs(slide / free / expected - 1.0) <= 1e-6, "with μ = 0.1 it slides, a = g (sin θ − μ cos θ)")

if failures:
    sys.exit("check_rolling: FAILED: " + "; ".join(failures))
print("check_rolling: ok")
