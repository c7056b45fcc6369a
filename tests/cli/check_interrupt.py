#!/usr/bin/env python3
"""check_interrupt.py — Ctrl-C stops `cdyn run` and `cdyn study` cleanly
(docs/outputs.md, docs/stability.md).

Usage: check_interrupt.py CDYN WORKDIR

1. The default membrane asked for 10^6 steps (far longer than the test waits) receives
   SIGINT once its history is being written.  Expected, from cmd_run.cpp's contract:
   - exit status 130 and one stderr line "interrupted after step K of 1000000";
   - the printed paragraph marked "INTERRUPTED after step K of 1000000 (partial results)";
   - summary.json with "partial": true, n_steps = K < n_steps_asked = 1000000;
   - history.csv complete for what was computed: rows for steps 0 … K, each with the
     columns of its header, and its energy E_total in the last row equal to
     summary.json's E_final (the same number, both printed with 17 digits);
   - no temporary files left (the AtomicFile names ".<name>.tmp-…").
2. A study of three runs receives SIGINT during its second (10^6 steps): it stops
   there, exit status 130; study.csv holds the two runs started, the second marked
   partial (column `partial`, error_kind "partial", no error), the third absent.
3. Ctrl-C while the plots are made (SIGINT to the whole process group, as a terminal
   sends it, once the plot script has started: CDYN_PYTHON is a wrapper that leaves
   a marker): no Python traceback, exit status 130, the data files complete
   (summary.json not partial, every history row), no temporary file (images
   included).  Skipped without a python3 that has matplotlib.
"""
import csv
import json
import os
import re
import signal
import subprocess
import sys
import shutil
import time

from cli_helpers import have_matplotlib

cdyn, workdir = sys.argv[1], sys.argv[2]


def wait_for_history(proc, out, what):
    """Until the time loop of the run in `out` runs: its history's temporary file has grown."""
    deadline = time.time() + 60
    while time.time() < deadline:
        temps = [f for f in os.listdir(out) if f.startswith(".history.csv.tmp")] if os.path.isdir(out) else []
        if temps and os.path.getsize(os.path.join(out, temps[0])) > 20000:
            return
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)
    sys.exit(f"check_interrupt: {what} never started writing its history")


def finish(proc):
    """stdout, stderr of proc; killed (and a failure) if it does not stop within 60 s."""
    try:
        return proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        sys.exit(f"check_interrupt: {proc.args[1]} did not stop within 60 s of the SIGINT")


out = os.path.join(workdir, "interrupt")
cmd = [cdyn, "run", "--out", out, "--set", "time.T=1000", "--set", "output.fields=false",
       "--set", "output.plots=false"]
proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
wait_for_history(proc, out, "the run")
proc.send_signal(signal.SIGINT)
stdout, err = finish(proc)

failures = []
def check(cond, what):
    if not cond:
        failures.append(what)

check(proc.returncode == 130, f"exit status {proc.returncode}, expected 130")
m = re.search(r"interrupted after step (\d+) of 1000000", err)
check(m is not None and len(err.strip().splitlines()) == 1, f"stderr: {err!r}")
check(m is not None and f"INTERRUPTED after step {m.group(1)} of 1000000 (partial results)" in stdout,
      f"the paragraph is not marked: {stdout!r}")
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

print(f"run: interrupted after step {K}: exit 130, partial summary, {K + 1} history rows, no temporaries")

# --- 2. a study ----------------------------------------------------------------------
study = os.path.join(workdir, "interrupt_study")
shutil.rmtree(study, ignore_errors=True)
proc = subprocess.Popen([cdyn, "study", "--out", study, "--vary", "time.dt=0.01,0.00001,0.000005",
                         "--set", "time.T=10"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                        start_new_session=True)
wait_for_history(proc, os.path.join(study, "run_001"), "the study's second run")
proc.send_signal(signal.SIGINT)
stdout, err = finish(proc)
check(proc.returncode == 130, f"study: exit status {proc.returncode}, expected 130")
check("study interrupted during run_001 (run 2 of 3)" in err, f"study: stderr {err!r}")
with open(os.path.join(study, "study.csv"), newline="") as f:
    rows = list(csv.DictReader(f))
check([r["run"] for r in rows] == ["run_000", "run_001"], f"study.csv rows {[r['run'] for r in rows]}")
check(rows[0]["partial"] == "false" and rows[0]["error_kind"] == "reference", f"study: run_000 {rows[0]}")
check(rows[1]["partial"] == "true" and rows[1]["error_kind"] == "partial" and rows[1]["error"] == "",
      f"study: run_001 {rows[1]}")
check(not os.path.exists(os.path.join(study, "run_002")), "study: the third run was started")
print(f"study: interrupted during run_001: exit 130, study.csv with run_000 and run_001 (partial)")

# --- 3. Ctrl-C during the plots -------------------------------------------------------
python = next((p for p in ["python3", "/usr/bin/python3"] if shutil.which(p) and subprocess.run(
    [p, "-c", "import matplotlib"], stderr=subprocess.DEVNULL).returncode == 0), None)
if python is None:
    print("plots: skipped (no python3 with matplotlib)")
else:
    out = os.path.join(workdir, "interrupt_plots")
    shutil.rmtree(out, ignore_errors=True)
    marker = os.path.join(workdir, "plot_started")
    if os.path.exists(marker):
        os.remove(marker)
    wrapper = os.path.join(workdir, "python_with_marker.sh")
    with open(wrapper, "w") as f:
        f.write(f"#!/bin/sh\ntouch '{marker}'\nexec '{shutil.which(python)}' \"$@\"\n")
    os.chmod(wrapper, 0o755)
    env = dict(os.environ, CDYN_PYTHON=wrapper)
    proc = subprocess.Popen([cdyn, "run", "--out", out, "--set", "mesh.n=10", "--set", "output.fields=false"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            start_new_session=True)  # its own process group, as a terminal's job
    deadline = time.time() + 60
    while not os.path.exists(marker) and time.time() < deadline and proc.poll() is None:
        time.sleep(0.02)
    time.sleep(0.3)  # into the script: matplotlib's import or the figures
    os.killpg(proc.pid, signal.SIGINT)
    stdout, err = finish(proc)
    check(proc.returncode == 130, f"plots: exit status {proc.returncode}, expected 130 ({err!r})")
    check("Traceback" not in err and "KeyboardInterrupt" not in err, f"plots: a traceback on stderr: {err!r}")
    check("interrupted after the time loop" in err, f"plots: stderr {err!r}")
    summary = json.load(open(os.path.join(out, "summary.json")))
    with open(os.path.join(out, "history.csv")) as f:
        n_rows = sum(1 for _ in f) - 1
    check(summary["partial"] is False and n_rows == summary["n_steps"] + 1 == 801, "plots: the data files are not complete")
    leftovers = [f for d in (out, os.path.join(out, "plots")) if os.path.isdir(d) for f in os.listdir(d) if ".tmp" in f]
    check(not leftovers, f"plots: temporary files left: {leftovers}")
    print("plots: interrupted: exit 130, no traceback, data complete, no temporaries")

if failures:
    print("check_interrupt: FAILED\n  " + "\n  ".join(failures))
    sys.exit(1)
print("check_interrupt: ok")
