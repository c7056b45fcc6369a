#!/usr/bin/python3
"""compare_getfem_3d.py — two of cdyn's 3D scenes against reference_scripts/getfem_dynamics_3d.py
(GetFEM's tetrahedral elements, scipy's sparse LU, its own active set loop), step by step.

    compare_getfem_3d.py CDYN GETFEM_SCRIPT SCENES_DIR WORKDIR MODEL PAIR SCHEME

MODEL membrane: data/scenes/membrane_3d.toml, n = 8, dt = 0.002, 400 steps;
MODEL elasticity: data/scenes/cube_3d.toml at n = 4 (the plane at z = −h/2), dt = 0.06
(the cube reaches the plane between steps, not at one: at t = 1.25 exactly the contact
would be grazing, λ = 0 on the bound, and either active set is right), 125 steps.

Compares, at every step, E_kin, E_pot, J (relative to J0), every probe the reference
writes, and the number of active constraints.  Both sides solve the same linear systems
to round-off (cdyn at solver.tol = 1e-13), and the pairs compared keep their difference
from growing (backward Euler damps it; P1+/P0 satisfies condition (12)): measured, with
up to 97 (membrane) and 25 (cube) active constraints, |ΔJ|/J0 ≤ 4.7e-12 and |Δu| ≤
6.4e-13, the active counts equal at every step.  The tolerance is 1e-10.  Midpoint runs
with time.reconstruct = false: the reference extrapolates U^{n+1} = 2U^{n+½} − Uⁿ.
"""
import os
import subprocess
import sys

from reference_histories import histories

CASES = {"membrane": ("membrane_3d.toml", 8, 0.002, 400, []),
         "elasticity": ("cube_3d.toml", 4, 0.06, 125, ["--set", "obstacle.point=[0, 0, -0.125]"])}

cdyn, script, scenes, work, model, pair, scheme = sys.argv[1:8]
scene, n, dt, steps, extra = CASES[model]
os.makedirs(work, exist_ok=True)
tag = f"{model}_{pair.replace('/', '_').replace('+', 'b')}_{scheme}"
ref = os.path.join(work, f"getfem_{tag}.csv")
subprocess.run(["/usr/bin/python3", script, "-model", model, "-pair", pair, "-scheme", scheme, "-n", str(n),
                "-dt", str(dt), "-steps", str(steps), "-out", ref], check=True)
out = os.path.join(work, f"cdyn_{tag}")
subprocess.run([cdyn, "run", os.path.join(scenes, scene), "--out", out, "--quiet", "--set", f"mesh.n={n}",
                "--set", f"method.pair={pair}", "--set", f"time.scheme={scheme}", "--set", f"time.dt={dt}",
                "--set", f"time.T={steps * dt}", "--set", "time.reconstruct=false", "--set", "solver.tol=1e-13",
                "--set", "output.fields=false", "--set", "output.plots=false", *extra], check=True)
a, b = histories(ref, out, "GetFEM")
J0 = abs(float(b[0]["E_total"]))
dJ = max(abs(float(x[k]) - float(y[k])) for x, y in zip(a, b) for k in ("E_total", "E_kin", "E_pot")) / J0
probes = [k for k in b[0] if "@" in k]
du = max(abs(float(x[k]) - float(y[k])) for x, y in zip(a, b) for k in probes)
mismatch = [(x["step"], x["active"], y["active"]) for x, y in zip(a, b) if x["active"] != y["active"]]
contact = sum(int(y["active"]) > 0 for y in b)
print(f"{model} {pair} {scheme}, {steps} steps ({contact} with contact, up to {max(int(y['active']) for y in b)} "
      f"active): max |dJ|/J0 = {dJ:.2e}, max |du| over {len(probes)} probes = {du:.2e}, "
      f"active-count mismatches {len(mismatch)} {mismatch[:5]}")
sys.exit(0 if dJ <= 1e-10 and du <= 1e-10 and not mismatch and contact > 0 else 1)
