"""The installed Python module (tests/install/run_install_test.cmake): imported from the
install tree, not the build tree; its directory is where the interpreter looks by itself
for the default prefix; `cdyn.run` gives the installed `cdyn run`'s energy drift.

Usage: python3 check_python_module.py INSTALLED_DIR DEFAULT_PREFIX_DIR CLI_RUN_DIR
(run from the directory holding CLI_RUN_DIR: `cdyn run --set mesh.n=4 --set time.T=0.01`).
"""

import json
import os
import sys

installed, default, cli_run = sys.argv[1:4]
import cdyn  # noqa: E402  (PYTHONPATH=INSTALLED_DIR)

if os.path.dirname(os.path.abspath(cdyn.__file__)) != os.path.join(os.path.abspath(installed), "cdyn"):
    sys.exit(f"cdyn was imported from {cdyn.__file__}, not from the install tree {installed}")
site = [p for p in sys.path if p != os.path.abspath(installed) and p not in os.environ.get("PYTHONPATH", "").split(":")]
if default not in site:
    sys.exit(f"{default} (the install directory under the default prefix) is not on {sys.executable}'s path: {site}")
r = cdyn.run(set=["mesh.n=4", "time.T=0.01"], out="installed_python_run")
with open(os.path.join(cli_run, "summary.json")) as f:
    cli = json.load(f)
if r["summary"]["E_rel_drift"] != cli["E_rel_drift"]:
    sys.exit(f"E_rel_drift: cdyn.run {r['summary']['E_rel_drift']!r}, cdyn run {cli['E_rel_drift']!r}")
print(f"python module {cdyn.__file__}: E_rel_drift {r['summary']['E_rel_drift']!r} as the installed cdyn run")
