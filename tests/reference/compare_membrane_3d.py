#!/usr/bin/python3
"""compare_membrane_3d.py — cdyn's 3D scalar wave with an obstacle (data/scenes/membrane_3d.toml)
against reference_scripts/getfem_membrane_3d.py (GetFEM's tetrahedral elements, scipy's
sparse LU, its own active set loop).

    compare_membrane_3d.py CDYN GETFEM_SCRIPT SCENE WORKDIR PAIR SCHEME STEPS

Compares, at every step, J, E_kin (relative to J0), u at the two probes and the number
of active vertex constraints.  Both sides solve the same linear systems to round-off and
the pairs compared keep their difference from growing (P1/P1 backward Euler damps it;
P1+/P0 satisfies condition (12)): measured over 400 steps with up to 97 active
constraints, |ΔJ|/J0 ≤ 4.3e-12 and |Δu| ≤ 1.0e-12, the active counts equal at every
step; the tolerance is 1e-10.  Midpoint runs with time.reconstruct = false: the script
extrapolates U^{n+1} = 2U^{n+½} − Uⁿ.
"""
import csv
import os
import subprocess
import sys

cdyn, script, scene, work, pair, scheme, steps = sys.argv[1:8]
os.makedirs(work, exist_ok=True)
tag = f"{pair.replace('/', '_').replace('+', 'b')}_{scheme}"
ref = os.path.join(work, f"getfem_membrane_3d_{tag}.csv")
subprocess.run(["/usr/bin/python3", script, "-pair", pair, "-scheme", scheme, "-n", "8", "-dt", "0.002",
                "-steps", steps, "-out", ref], check=True)
out = os.path.join(work, f"cdyn_membrane_3d_{tag}")
subprocess.run([cdyn, "run", scene, "--out", out, "--quiet", "--set", "mesh.n=8", "--set", f"method.pair={pair}",
                "--set", f"time.scheme={scheme}", "--set", "time.dt=0.002", "--set", f"time.T={int(steps) * 0.002}",
                "--set", "time.reconstruct=false", "--set", "output.fields=false", "--set", "output.plots=false"],
               check=True)
with open(ref) as f:
    b = list(csv.DictReader(f))
with open(os.path.join(out, "history.csv")) as f:
    a = list(csv.DictReader(f))
if len(a) != len(b):
    sys.exit(f"FAIL: {len(a)} cdyn rows against {len(b)} GetFEM rows")
J0 = abs(float(b[0]["E_total"]))
dJ = max(abs(float(x[k]) - float(y[k])) for x, y in zip(a, b) for k in ("E_total", "E_kin")) / J0
du = max(abs(float(x[f"u@{p}"]) - float(y[f"u_{p}"])) for x, y in zip(a, b) for p in ("centre", "low"))
mismatch = [(x["step"], x["active"], y["active"]) for x, y in zip(a, b) if x["active"] != y["active"]]
contact = sum(int(y["active"]) > 0 for y in b)
print(f"{pair} {scheme}, {steps} steps ({contact} with contact, up to {max(int(y['active']) for y in b)} active): "
      f"max |dJ|/J0 = {dJ:.2e}, max |du| = {du:.2e}, active-count mismatches {len(mismatch)} {mismatch[:5]}")
sys.exit(0 if dJ <= 1e-10 and du <= 1e-10 and not mismatch and contact > 0 else 1)
