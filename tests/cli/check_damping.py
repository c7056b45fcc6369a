#!/usr/bin/env python3
"""check_damping.py — Rayleigh damping through the command line (docs/schemes.md,
"Rayleigh damping"; docs/outputs.md, the column `dissipated`).

Usage: check_damping.py CDYN SOURCE_DIR WORKDIR

data/scenes/damped_disk.toml (the disk dropped from rest, α = 100 /s, β = 5e-4 s,
discrete_gradient):
  - history.csv has the column `dissipated` (W_d from t = 0, non-decreasing) and
    J + W_d = J0 on every row: discrete_gradient balances each step to time.energy_tol
    (measured max |J + W_d − J0| = 2.2e-12 E_scale; asserted 1e-9);
  - summary.json: `damping` = {alpha, beta}, `dissipated_work` = the last row's W_d,
    E_abs_drift = max |J + W_d − J0| (the drift of the balance, not of J, which loses
    6.5 E_scale);
  - the disk comes to rest: E_kin(T) below 1e-6 of its largest value (measured 1e-7)
    and the contact force equal to the weight ρπR²g = 12.33 N/mm within 1 % (the mesh's
    area is within 0.3 % of πR²; measured 12.29).
The same scene without damping keeps bouncing (E_kin(T) above 1 % of its largest): the
check above could fail.  Only the standard library is used.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import check, failures, run  # noqa: E402

cdyn, src, work = sys.argv[1:4]
scene = os.path.join(src, "data/scenes/damped_disk.toml")

s, rows, _ = run(cdyn, scene, os.path.join(work, "damped"))
J0 = rows[0]["E_total"]
W = [r["dissipated"] for r in rows]
balance = max(abs(r["E_total"] + r["dissipated"] - J0) for r in rows) / s["E_scale"]
print(f"damped disk: max |J + W_d - J0|/E_scale = {balance:.2e}, W_d(T) = {W[-1]:.4f}, J(T) = {rows[-1]['E_total']:.4f}")
check(balance <= 1e-9, "J + W_d = J0 on every row")
check(all(b >= a for a, b in zip(W, W[1:])) and W[-1] > 0, "W_d is non-decreasing and positive")
check(s["damping"] == {"alpha": 100.0, "beta": 5e-4}, f"summary.json damping: {s['damping']}")
check(s["dissipated_work"] == W[-1], "dissipated_work is the last row's W_d")
check(abs(s["E_abs_drift"] / s["E_scale"] - balance) <= 1e-12, "E_abs_drift is the drift of J + W_d")

kinetic = [r["E_kin"] for r in rows]
weight = 1e-6 * math.pi * 20.0 ** 2 * 9810.0
print(f"  E_kin(T)/max E_kin = {kinetic[-1] / max(kinetic):.2e}, contact force {rows[-1]['contact_force']:.4f} "
      f"(weight {weight:.4f})")
check(kinetic[-1] <= 1e-6 * max(kinetic), "the damped disk comes to rest")
check(abs(rows[-1]["contact_force"] / weight - 1.0) <= 0.01, "the contact force is the weight at rest")

s0, rows0, _ = run(cdyn, scene, os.path.join(work, "undamped"), "damping.alpha=0", "damping.beta=0")
kinetic0 = [r["E_kin"] for r in rows0]
print(f"  without damping: E_kin(T)/max E_kin = {kinetic0[-1] / max(kinetic0):.2e}")
check("dissipated" not in rows0[0] and s0["dissipated_work"] == 0.0 and s0["damping"] is None,
      "without damping: no column, W_d = 0, damping null")
check(kinetic0[-1] > 1e-2 * max(kinetic0), "without damping the disk keeps moving")

if failures:
    sys.exit("check_damping: FAILED: " + "; ".join(failures))
print("check_damping: ok")
