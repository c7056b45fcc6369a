#!/bin/sh
# disk_convergence.sh — the falling disk (data/scenes/disk.toml) under refinement: the
# contact duration, the peak contact force and the energy after the rebound for a
# sequence of meshes and steps refined together (lc and dt halved at each level), for
# the well-posed P1+/P0 pair and the redistributed mass, midpoint scheme.  Prints a
# Markdown table per method with each level's relative difference to the finest one,
# and a second one with the impulse, centroid and width of the contact-force history
# and their observed orders (docs/experiments.md, "The falling disk").
#
#   scripts/disk_convergence.sh [BUILD_DIR] [LEVELS]   # default build, 4 levels
#
# Meshes: gmsh -2 -setnumber lc LC data/geo/disk.geo (lc = 5, 2.5, 1.25, 0.625 mm) into
# out/disk_convergence/; each run writes out/disk_convergence/<method>_<level>/.
# About 20 s on one core for 4 levels, 5 minutes for 5 (the finest P1+/P0 level: 91k dofs, 8000 steps).
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

def rates(q):
    """Observed orders log2(|q_k − q_{k+1}| / |q_{k+1} − q_{k+2}|) (h and dt halved per level)."""
    d = [abs(q[k] - q[k + 1]) for k in range(len(q) - 1)]
    return [math.log2(d[k] / d[k + 1]) if d[k + 1] > 0 and d[k] > 0 else float("nan") for k in range(len(d) - 1)]

for name in ("P1p_P0", "redistributed"):
    runs = []
    for k in range(levels):
        with open(os.path.join(out, f"{name}_{k}", "summary.json")) as f:
            runs.append(json.load(f))
    label = name.replace("p", "+").replace("_", "/")
    print(f"\n{label}, midpoint: the raw impact figures\n")
    print("| h (mm) | dt (s) | dofs | contact duration (ms) | rel. diff. to finest | peak force (N/mm) "
          "| rel. diff. to finest | J_after/J0 − 1 | p_y after (N·s/mm) | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    fin = runs[-1]["impact"]
    for s in runs:
        i = s["impact"]
        d = [abs(i[c] - fin[c]) / abs(fin[c]) for c in ("contact_duration", "peak_force")]
        a = i["after"]
        print(f"| {s['h']:.3g} | {s['dt']:.3g} | {s['n_dofs']} | {1e3 * i['contact_duration']:.3f} | {d[0]:.1e} | "
              f"{i['peak_force']:.1f} | {d[1]:.1e} | {a['E'] / s['E0'] - 1 if a else float('nan'):.1e} | "
              f"{a['momentum'][1] if a else float('nan'):.4f} | {s['wall_s']:.2f} |")
    # The smooth functionals of the force history (contact_history.hpp) and their orders.
    keys = ("impulse", "t_force_centroid", "force_width", "half_sine_peak_force")
    q = {c: [s["impact"][c] for s in runs] for c in keys}
    r = {c: rates(q[c]) for c in keys}
    print(f"\n{label}, midpoint: impulse, centroid and width of the force history (order p from three levels)\n")
    print("| h (mm) | dt (s) | impulse I (N·s/mm) | p | centroid t̄ (ms) | p | width σ (ms) | p | half-sine T (ms) | half-sine peak (N/mm) | p |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for k, s in enumerate(runs):
        i = s["impact"]
        o = {c: (f"{r[c][k - 2]:.2f}" if k >= 2 else "") for c in keys}
        print(f"| {s['h']:.3g} | {s['dt']:.3g} | {i['impulse']:.6f} | {o['impulse']} | {1e3 * i['t_force_centroid']:.5f} | "
              f"{o['t_force_centroid']} | {1e3 * i['force_width']:.5f} | {o['force_width']} | "
              f"{1e3 * i['half_sine_duration']:.4f} | {i['half_sine_peak_force']:.2f} | {o['half_sine_peak_force']} |")
PY
