#!/usr/bin/env python3
"""check_restart.py — checkpoints and `cdyn run --resume` (docs/outputs.md, "Restart").

Usage: check_restart.py CDYN SOURCE_DIR WORKDIR

The scene: data/scenes/damped_disk.toml for 3000 steps (T = 0.3 s, about 2 s), with
output.checkpoint_every = 50: elasticity (contact.csv, the impact summary, the
penetration), Rayleigh damping (the column `dissipated`), discrete_gradient (whose
memory holds Ψ(qⁿ) and two warm starts), the field series.
 1. The run uninterrupted: the reference.  Its checkpoint folder is gone at the end.
 2. The same run killed with SIGKILL once its first checkpoint exists, then
    `cdyn run --resume`: the history.csv rows are the reference's, every column but
    the timings `solve_s`, `step_s`, `reconstruction_s` equal as text (17 digits: bit for bit); contact.csv,
    fields.pvd and every fields/*.vtu byte for byte; summary.json's keys equal but the timings,
    `written` and `resumed_at` (the checkpoint's step, a multiple of 50: at most 50 steps
    lost).
 3. The same run stopped by SIGINT (Ctrl-C): exit 130, a checkpoint of the last step
    (resumed_at = summary.json's n_steps of the interrupted run: nothing lost), and the
    resumed run equal to the reference again.
 4. Refused with exit status 2 and one line on stderr naming the file or option: a flipped
    byte in checkpoint/state.bin, a changed byte in the journal checkpoint/history.csv, a
    scene.toml edited after the checkpoint (another time.dt), --resume with --set, a
    run directory without checkpoint (a completed run).
Only the standard library is used.
"""
import filecmp
import json
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import check, failures  # noqa: E402

cdyn, src, work = sys.argv[1:4]
scene = os.path.join(src, "data/scenes/damped_disk.toml")
SETS = ["time.T=0.3", "output.checkpoint_every=50", "output.plots=false", "output.stress=false"]
TIMING = {"setup_s", "wall_s", "s_per_step", "qp_s_per_step", "reconstruction_s_per_step", "fields_s", "written",
          "resumed_at"}


def command(out):
    args = [cdyn, "run", scene, "--out", out, "--quiet"]
    for s in SETS:
        args += ["--set", s]
    return args


def fresh(name):
    out = os.path.join(work, name)
    shutil.rmtree(out, ignore_errors=True)
    return out


def resume(out):
    return subprocess.run([cdyn, "run", "--resume", out, "--quiet"], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)


def stopped_run(name, sig):
    """The run started, sent `sig` once its first checkpoint exists; its directory."""
    out = fresh(name)
    proc = subprocess.Popen(command(out), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    state = os.path.join(out, "checkpoint", "state.bin")
    deadline = time.time() + 60
    while not os.path.exists(state) and proc.poll() is None and time.time() < deadline:
        time.sleep(0.002)
    check(proc.poll() is None, f"{name}: the run was still running at its first checkpoint")
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    return out, proc.returncode, err


def compare(out, ref, what):
    """The resumed run in `out` against the uninterrupted one in `ref`."""
    rows = open(os.path.join(out, "history.csv")).read().splitlines()
    ref_rows = open(os.path.join(ref, "history.csv")).read().splitlines()
    header = ref_rows[0].split(",")
    timing = {k for k, name in enumerate(header) if name in ("solve_s", "step_s", "reconstruction_s")}
    strip = lambda line: [c for k, c in enumerate(line.split(",")) if k not in timing]  # noqa: E731
    check(len(rows) == len(ref_rows) == 3002, f"{what}: {len(rows)} history lines, expected 3002 (a header, steps 0 … 3000)")
    same = sum(strip(a) == strip(b) for a, b in zip(rows, ref_rows))
    check(same == len(ref_rows), f"{what}: history.csv rows equal but the timings ({same} of {len(ref_rows)})")
    check(filecmp.cmp(os.path.join(out, "contact.csv"), os.path.join(ref, "contact.csv"), shallow=False),
          f"{what}: contact.csv byte for byte")
    check(filecmp.cmp(os.path.join(out, "fields.pvd"), os.path.join(ref, "fields.pvd"), shallow=False),
          f"{what}: fields.pvd byte for byte")
    frames = sorted(os.listdir(os.path.join(ref, "fields")))
    check(frames == sorted(os.listdir(os.path.join(out, "fields"))), f"{what}: the same field files")
    match, mismatch, errors = filecmp.cmpfiles(os.path.join(ref, "fields"), os.path.join(out, "fields"), frames,
                                               shallow=False)
    check(not mismatch and not errors, f"{what}: every fields/*.vtu byte for byte ({len(match)} files)")
    s, r = (json.load(open(os.path.join(d, "summary.json"))) for d in (out, ref))
    differ = [k for k in r if k not in TIMING and s.get(k) != r[k]]
    check(not differ and set(s) == set(r), f"{what}: summary.json equal but timings (differ: {differ})")
    check(not os.path.exists(os.path.join(out, "checkpoint")), f"{what}: no checkpoint left after completion")
    return s


ref = fresh("reference")
subprocess.run(command(ref), check=True)
check(not os.path.exists(os.path.join(ref, "checkpoint")), "reference: the checkpoint removed at completion")
check(json.load(open(os.path.join(ref, "summary.json")))["resumed_at"] is None, "reference: resumed_at null")

# 2. SIGKILL, then --resume
killed, status, _ = stopped_run("killed", signal.SIGKILL)
check(status == -signal.SIGKILL, f"killed: status {status}")
check(not os.path.exists(os.path.join(killed, "summary.json")), "killed: no summary.json")
r = resume(killed)
check(r.returncode == 0, f"resume after SIGKILL: exit status {r.returncode}: {r.stderr}")
s = compare(killed, ref, "SIGKILL + resume")
print(f"SIGKILL: resumed at step {s['resumed_at']} of 3000")
check(s["resumed_at"] % 50 == 0 and 0 < s["resumed_at"] < 3000, f"resumed_at {s['resumed_at']}: a checkpoint step")

# 3. Ctrl-C, then --resume: the checkpoint is the interrupted step's
stopped, status, err = stopped_run("interrupted", signal.SIGINT)
check(status == 130 and "--resume" in err, f"Ctrl-C: status {status}, stderr {err!r}")
done = json.load(open(os.path.join(stopped, "summary.json")))["n_steps"]
r = resume(stopped)
check(r.returncode == 0, f"resume after Ctrl-C: exit status {r.returncode}: {r.stderr}")
s = compare(stopped, ref, "Ctrl-C + resume")
print(f"Ctrl-C after step {done}: resumed at step {s['resumed_at']}")
check(s["resumed_at"] == done, f"Ctrl-C: resumed at {s['resumed_at']}, the run had stopped after {done}")


# 4. refusals
def refused(out, pattern, what, args=None):
    r = subprocess.run(args or [cdyn, "run", "--resume", out], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       text=True)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and pattern in r.stderr,
          f"{what}: exit {r.returncode}, stderr {r.stderr.strip()!r} (expected one line with {pattern!r})")


def killed_copy(name):
    out = fresh(name)
    shutil.copytree(base, out)
    return out


base, _, _ = stopped_run("refusals", signal.SIGKILL)
out = killed_copy("corrupt_state")
with open(os.path.join(out, "checkpoint", "state.bin"), "r+b") as f:
    f.seek(200)
    b = f.read(1)
    f.seek(200)
    f.write(bytes([b[0] ^ 1]))
refused(out, "state.bin: not a valid checkpoint: its checksum does not match", "a flipped byte in state.bin")
out = killed_copy("corrupt_journal")
with open(os.path.join(out, "checkpoint", "history.csv"), "r+b") as f:
    f.seek(100)
    f.write(b"9")
refused(out, "history.csv: does not match its checkpoint", "a changed byte in the history journal")
out = killed_copy("other_scene")
text = open(os.path.join(out, "scene.toml")).read()
open(os.path.join(out, "scene.toml"), "w").write(text.replace("dt = 0.0001", "dt = 0.0002"))
check("dt = 0.0002" in open(os.path.join(out, "scene.toml")).read(), "the scene.toml edit took")
refused(out, "state.bin: written for another scene", "an edited scene.toml")
refused(base, "--resume: ", "--resume with --set", [cdyn, "run", "--resume", base, "--set", "time.T=1"])
refused(ref, "no checkpoint to resume from", "a completed run")
r = resume(base)  # the untouched copy still resumes
check(r.returncode == 0, f"the untouched killed run resumes: {r.stderr}")

if failures:
    sys.exit("check_restart: FAILED: " + "; ".join(failures))
print("check_restart: ok")
