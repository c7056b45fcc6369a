#!/bin/sh
# disk_convergence.sh — the falling disk (data/scenes/disk.toml) under refinement: the
# contact duration, the peak contact force and the energy after the rebound for a
# sequence of meshes and steps refined together (lc and dt halved at each level), for
# the well-posed P1+/P0 pair and the redistributed mass, midpoint scheme.  Prints a
# Markdown table per method with each level's relative difference to the finest one
# (docs/experiments.md, "The falling disk").
#
#   scripts/disk_convergence.sh [BUILD_DIR] [LEVELS]   # default build, 4 levels
#
# Meshes: gmsh -2 -setnumber lc LC data/geo/disk.geo (lc = 5, 2.5, 1.25, 0.625 mm) into
# out/disk_convergence/; each run writes out/disk_convergence/<method>_<level>/.
# About a minute on one core for 4 levels.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
levels=${2:-4}
cdyn=$build/apps/cdyn
out=$root/out/disk_convergence
mkdir -p "$out"

level=0
lc=5
dt=2e-5
while [ "$level" -lt "$levels" ]; do
  gmsh -2 -setnumber lc "$lc" "$root/data/geo/disk.geo" -o "$out/disk_$level.msh" -format msh41 >/dev/null
  for method in "method.pair=P1+/P0" "method.mass=redistributed"; do
    name=$(echo "$method" | sed 's/.*=//; s|/|_|; s/+/p/')
    "$cdyn" run "$root/data/scenes/disk.toml" --out "$out/${name}_$level" --quiet \
      --set "mesh.file=$out/disk_$level.msh" --set "time.dt=$dt" --set "$method" \
      --set output.fields=false --set output.plots=false --set output.contact_every=100000000
  done
  level=$((level + 1))
  lc=$(awk "BEGIN { print $lc / 2 }")
  dt=$(awk "BEGIN { print $dt / 2 }")
done

/usr/bin/python3 - "$out" "$levels" <<'PY'
import json, math, os, sys
out, levels = sys.argv[1], int(sys.argv[2])
for name in ("P1p_P0", "redistributed"):
    rows = []
    for k in range(levels):
        with open(os.path.join(out, f"{name}_{k}", "summary.json")) as f:
            s = json.load(f)
        i = s["impact"]
        rows.append((s["h"], s["dt"], s["n_dofs"], i["contact_duration"], i["peak_force"],
                     i["after"]["E"] / s["E0"] if i["after"] else float("nan"),
                     i["after"]["momentum"][1] if i["after"] else float("nan"), s["wall_s"]))
    print(f"\n{name.replace('p', '+').replace('_', '/')}, midpoint\n")
    print("| h (mm) | dt (s) | dofs | contact duration (ms) | rel. diff. to finest | peak force (N/mm) "
          "| rel. diff. to finest | J_after/J0 − 1 | p_y after (N·s/mm) | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    fin = rows[-1]
    for r in rows:
        d = [abs(r[c] - fin[c]) / abs(fin[c]) for c in (3, 4)]
        print(f"| {r[0]:.3g} | {r[1]:.3g} | {r[2]} | {1e3 * r[3]:.3f} | {d[0]:.1e} | {r[4]:.1f} | {d[1]:.1e} | "
              f"{r[5] - 1:.1e} | {r[6]:.4f} | {r[7]:.2f} |")
PY
