#!/bin/sh
# experiments.sh — the seed's numerical experiments (and the oscillator's) re-run with
# cdyn, then the figures and the table of docs/experiments.md.
#
#   scripts/experiments.sh [BUILD_DIR]        (default build/; writes out/experiments/
#                                              and docs/img/experiments_*.png)
set -eu
cd "$(dirname "$0")/.."
cdyn="${1:-build}/apps/cdyn"
out=out/experiments
mkdir -p "$out"
quiet="--quiet --set output.fields=false --set output.plots=false"

run() {  # name, then --set overrides of the default (membrane) scene or of a scene file
  name=$1; shift
  $cdyn run "$@" --out "$out/$name" $quiet
}

# The seed's membrane: h = 0.1, dt = 0.001, T = 0.8 (slides "P1+/P0 method, h = 0.1, ...").
for pair in P1+/P0 P1/P0 P1/P1 P1+/P1 P2/P1; do
  run "membrane_midpoint_$(echo "$pair" | sed 's/+/b/;s#/#_#')" --set mesh.n=10 --set method.pair="$pair"
done
for pair in P1+/P0 P1/P0; do
  run "membrane_backward_euler_$(echo "$pair" | sed 's/+/b/;s#/#_#')" --set mesh.n=10 --set method.pair="$pair" \
      --set time.scheme=backward_euler
done
run membrane_midpoint_P1b_P0_h005 --set mesh.n=20
# The seed's algorithm as published: U^{n+1} = 2U^{n+½} − Uⁿ left as it comes (no
# reconstruction of eq. (14)), and the energy-exact scheme, for P1+/P0.
for pair in P1+/P0 P2/P1 P1+/P1; do
  run "membrane_midpoint_extrapolated_$(echo "$pair" | sed 's/+/b/;s#/#_#')" --set mesh.n=10 --set method.pair="$pair" \
      --set time.reconstruct=false
done
run membrane_discrete_gradient_P1b_P0 --set mesh.n=10 --set time.scheme=discrete_gradient
run membrane_discrete_gradient_P1b_P0_h005 --set mesh.n=20 --set time.scheme=discrete_gradient
# The same membrane with the classical schemes of the comparison (standard mass).
run membrane_energy_conserving_consistent --set mesh.n=10 --set method.mass=consistent --set time.scheme=energy_conserving
run membrane_paoli_schatzman_lumped --set mesh.n=10 --set method.mass=lumped --set time.scheme=paoli_schatzman \
    --set time.dt=0.0005 --set time.restitution=0

# The one-dof oscillator: what each scheme selects among the solutions u = a|cos t|.
for scheme in midpoint midpoint_end backward_euler newmark energy_conserving; do
  run "oscillator_$scheme" data/scenes/oscillator.toml --set time.scheme=$scheme
done
for e in 0 0.5 1; do
  run "oscillator_paoli_schatzman_e$e" data/scenes/oscillator.toml --set time.scheme=paoli_schatzman \
      --set time.restitution=$e
done

/usr/bin/python3 scripts/plot_experiments.py "$out" docs/img
