#!/usr/bin/env python3
"""check_interrupt.py — Ctrl-C stops `cdyn run` cleanly (docs/outputs.md, docs/stability.md).

Usage: check_interrupt.py CDYN WORKDIR

The default membrane asked for 10^6 steps (far longer than the test waits) receives
SIGINT once its history is being written.  Expected, from cmd_run.cpp's contract:
  - exit status 130 and one stderr line "interrupted after step K of 1000000";
  - summary.json with "partial": true, n_steps = K < n_steps_asked = 1000000;
  - history.csv complete for what was computed: rows for steps 0 … K, each with the
    columns of its header, and its energy E_total in the last row equal to
    summary.json's E_final (the same number, both printed with 17 digits);
  - no temporary files left (the AtomicFile names ".<name>.tmp-…").
"""
import csv
import json
import os
import re
import signal
import subprocess
import sys
import time

cdyn, workdir = sys.argv[1], sys.argv[2]
out = os.path.join(workdir, "interrupt")
cmd = [cdyn, "run", "--out", out, "--quiet", "--set", "time.T=1000", "--set", "output.fields=false",
       "--set", "output.plots=false"]
proc = subprocess.Popen(cmd, stderr=subprocess.PIPE, text=True)
# Wait until the time loop runs: the history's temporary file exists and has grown.
deadline = time.time() + 60
while time.time() < deadline:
    temps = [f for f in os.listdir(out) if f.startswith(".history.csv.tmp")] if os.path.isdir(out) else []
    if temps and os.path.getsize(os.path.join(out, temps[0])) > 20000:
        break
    time.sleep(0.05)
else:
    proc.kill()
    sys.exit("check_interrupt: the run never started writing its history")
proc.send_signal(signal.SIGINT)
_, err = proc.communicate(timeout=60)

failures = []
def check(cond, what):
    if not cond:
        failures.append(what)

check(proc.returncode == 130, f"exit status {proc.returncode}, expected 130")
m = re.search(r"interrupted after step (\d+) of 1000000", err)
check(m is not None and len(err.strip().splitlines()) == 1, f"stderr: {err!r}")
summary = json.load(open(os.path.join(out, "summary.json")))
K = summary["n_steps"]
check(summary["partial"] is True, "summary.json: partial is not true")
check(summary["n_steps_asked"] == 1000000, "summary.json: n_steps_asked")
check(0 < K < 1000000, f"summary.json: n_steps = {K}")
check(m is None or int(m.group(1)) == K, "stderr and summary.json disagree on the step")
with open(os.path.join(out, "history.csv")) as f:
    rows = list(csv.reader(f))
header, body = rows[0], rows[1:]
check(len(body) == K + 1, f"history.csv has {len(body)} rows, expected {K + 1}")
check(all(len(r) == len(header) for r in body), "history.csv: a row with missing columns")
check([int(r[0]) for r in body] == list(range(K + 1)), "history.csv: steps are not 0 … K")
check(float(body[-1][header.index("E_total")]) == summary["E_final"], "E_final differs from the last history row")
leftovers = [f for f in os.listdir(out) if ".tmp-" in f]
check(not leftovers, f"temporary files left: {leftovers}")

if failures:
    print("check_interrupt: FAILED\n  " + "\n  ".join(failures))
    sys.exit(1)
print(f"check_interrupt: interrupted after step {K}: exit 130, partial summary, {K + 1} history rows, no temporaries")
