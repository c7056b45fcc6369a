#!/usr/bin/python3
"""compare_bar.py — cdyn's clamped bar against reference_scripts/getfem_bar.py (GetFEM's
matrices, each step's one-bound QP solved in closed form), consistent mass.

    compare_bar.py CDYN GETFEM_SCRIPT SCENE WORKDIR SCHEME STEPS

Compares, at every step, J (relative to J0) and u at the contact end, to 1e-10: both
sides solve the same linear systems exactly up to round-off (measured 8e-14).  Midpoint
is compared over its first 88 steps (the first contact begins at step 80): the
consistent mass violates condition (12), and from the first impact on the two runs'
1e-13 difference grows about 10× every 8 steps, to O(1) by step 330
(docs/verification.md).
"""
import os
import subprocess
import sys

from reference_histories import histories

cdyn, script, scene, work, scheme, steps = sys.argv[1:7]
os.makedirs(work, exist_ok=True)
ref = os.path.join(work, f"getfem_bar_{scheme}.csv")
subprocess.run(["/usr/bin/python3", script, "-n", "40", "-dt", "0.0125", "-steps", steps, "-scheme", scheme,
                "-out", ref], check=True)
out = os.path.join(work, f"cdyn_bar_{scheme}")
subprocess.run([cdyn, "run", scene, "--out", out, "--quiet", "--set", "method.mass=consistent", "--set",
                f"time.scheme={scheme}", "--set", f"time.T={int(steps) * 0.0125}", "--set", "solver.tol=1e-13",
                "--set", "output.fields=false", "--set", "output.plots=false"], check=True)
a, b = histories(ref, out, "GetFEM")
J0 = float(b[0]["E_total"])
dJ = max(abs(float(x["E_total"]) - float(y["E_total"])) for x, y in zip(a, b)) / J0
du = max(abs(float(x["u@contact"]) - float(y["u_contact"])) for x, y in zip(a, b))
contact = sum(float(y["u_contact"]) <= 1e-14 for y in b)
print(f"bar, consistent mass, {scheme}, {steps} steps ({contact} with the end on the obstacle): "
      f"max |dJ|/J0 = {dJ:.2e}, max |du(0)| = {du:.2e}")
sys.exit(0 if dJ <= 1e-10 and du <= 1e-10 else 1)
