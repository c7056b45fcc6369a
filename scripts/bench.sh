#!/bin/sh
# bench.sh — runs the benchmark set of docs/performance.md, 14 minutes on the 2-core
# machine when idle (keep it idle: every figure is a wall time).  Usage: scripts/bench.sh [BUILD_DIR] [OUT_DIR]
# BUILD_DIR must be a Release build with the targets cdyn_app, bench_contact_step, bench_step_solvers,
# bench_condition12, bench_bandwidth, bench_threads and bench_subdomains built (cmake --build BUILD --target
# cdyn_app bench_contact_step bench_step_solvers bench_condition12 bench_bandwidth bench_threads bench_subdomains).
set -e
BUILD=${1:-build}
OUT=${2:-out/bench}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PY=/usr/bin/python3
# One core for every timing that compares ratios: the kernel's loops (OpenMP) and OpenBLAS
# (under CHOLMOD's supernodal solves) would otherwise take both, and a ratio would then
# compare parts that use the second core differently (the linear step's forward/back
# solve barely, the contact step's CG fully).  Only (i), the speed-up of two threads over
# one, sets its counts itself (solver.threads, set_thread_count), both in the same run.
export OMP_NUM_THREADS=1
export OPENBLAS_NUM_THREADS=1
# And the same core for all of them (CDYN_BENCH_CPU, by default the first this shell may
# use): the two cores of the virtual machine in docs/performance.md are not equally fast
# (the second ran the linear impact window 1.2–2.2 times slower), and a ratio's two runs
# on different cores measured the cores.  (i) chooses its cores itself.
CPU=${CDYN_BENCH_CPU:-$($PY -c 'import os; print(min(os.sched_getaffinity(0)))')}
ONE="taskset -c $CPU"
mkdir -p "$OUT"
START=$(date +%s)
# A section header with the seconds since the start (the sections' own durations).
section() { echo "== $1 [+$(( $(date +%s) - START )) s]"; }
echo "== load average: $(cut -d' ' -f1-3 /proc/loadavg); one-core figures on CPU $CPU"
section "(a) contact overhead, membrane P1+/P0 midpoint n = 160, steps 211-310 (n = 80: CDYN_BENCH_N=80, not run here)"
$ONE "$BUILD/bench/bench_contact_step" --benchmark_counters_tabular=true --benchmark_filter='condense:1' \
    --benchmark_enable_random_interleaving=true
section "(b) cdyn vs FreeFEM + ff-Ipopt, P1/P1 backward Euler, the impact window: steps 241-300, n = 40, 80, 160"
$ONE $PY "$ROOT/bench/bench_peer.py" "$BUILD/apps/cdyn" "$OUT/peer" --n 40,80,160 --steps 300 --first 241
section "(b') the same in resting contact (started on the obstacle): steps 1-50 at n = 40, 80, 1-30 at n = 160"
$ONE $PY "$ROOT/bench/bench_peer.py" "$BUILD/apps/cdyn" "$OUT/peer_resting" --n 40,80 --steps 50 --resting
$ONE $PY "$ROOT/bench/bench_peer.py" "$BUILD/apps/cdyn" "$OUT/peer_resting" --n 160 --steps 30 --resting
section "(c) scaling n = 40 ... 640: free flight (steps 1-20), then resting contact (started on the obstacle, steps 1-30)"
$ONE $PY "$ROOT/bench/bench_scaling.py" "$BUILD/apps/cdyn" "$OUT/scaling" --steps 20 --no-wellposed
$ONE $PY "$ROOT/bench/bench_scaling.py" "$BUILD/apps/cdyn" "$OUT/scaling_resting" --steps 30 --resting --no-wellposed
section "(d) solver table on the same steps"
$ONE "$BUILD/bench/bench_step_solvers" --benchmark_counters_tabular=true
section "(e) speed against error (cdyn study)"
$ONE "$BUILD/apps/cdyn" study "$ROOT/data/scenes/membrane.toml" --vary method.pair=P1+/P0,P1/P1 \
    --vary time.scheme=midpoint,backward_euler --vary mesh.n=10,20,40 --vary time.dt=0.004,0.002,0.001 \
    --out "$OUT/study_membrane"
$ONE "$BUILD/apps/cdyn" study "$ROOT/data/scenes/bar.toml" --vary method.pair=P1+/P0,P1/P1,P1/P0 \
    --vary time.scheme=midpoint,backward_euler --vary mesh.n=20,40,80,160 --vary time.dt=0.02,0.01,0.005 \
    --out "$OUT/study_bar"
section "(g) the published table: extrapolated, reconstructed and discrete_gradient full steps"
$ONE $PY "$ROOT/bench/bench_published_table.py" "$BUILD/apps/cdyn" "$OUT/published"
section "(h) contact in every regime: impact, resting, chatter, disk, beam (P1+/P0 midpoint, P1/P1 backward Euler), about 1.5 minutes"
$ONE $PY "$ROOT/bench/bench_regimes.py" "$BUILD/apps/cdyn" "$ROOT" "$OUT/regimes" --repeat 2
section "(j) friction: the frictional contact step against the frictionless one, disk and ramp, backward Euler"
$ONE $PY "$ROOT/bench/bench_friction.py" "$BUILD/apps/cdyn" "$ROOT" "$OUT/friction" --repeat 2
section "(f) condition (12) at any size: beta of the membrane P1+/P0, n = 40 ... 577 (1M dofs), about 1.5 minutes"
CDYN_BENCH_N=40,80,160,320,577 $ONE "$BUILD/bench/bench_condition12" --benchmark_counters_tabular=true
section "(i) the machine's ceiling for two threads: STREAM triad and the threaded S x, 1 and 2 threads"
"$BUILD/bench/bench_bandwidth" --benchmark_enable_random_interleaving=true
section "(i) both cores: the impact window on 1 and 2 threads, n = 320 and 640, P1+/P0 midpoint and P1/P1 backward Euler, about 2 minutes"
"$BUILD/bench/bench_threads" --benchmark_counters_tabular=true --benchmark_enable_random_interleaving=true
section "(k) three dimensions: the cube's contact step against its unknowns, the CG path to n = 32, the factor to n = 16"
# (the factor at n = 24, 1 more minute: --linear factor --sizes 24; at n = 32, 3.5 more minutes)
$ONE $PY "$ROOT/bench/bench_three_d.py" "$BUILD/apps/cdyn" "$ROOT" "$OUT/three_d" --sizes 8,16,24,32 --linear cg
$ONE $PY "$ROOT/bench/bench_three_d.py" "$BUILD/apps/cdyn" "$ROOT" "$OUT/three_d" --sizes 8,16 --linear factor
if [ -f "$BUILD/kernel/libcdyn_petsc.so" ]; then
  section "(l) the PETSc back end on 1 and 2 ranks: the cube's step QP, strong scaling (docs/distributed.md), about 2.5 minutes"
  $PY "$ROOT/bench/bench_mpi.py" "$BUILD/apps/cdyn" "$(command -v mpiexec)" "$ROOT" "$OUT/mpi" --sizes 16,32 --pcs jacobi --native cg --log
  section "(m) subdomains: the cube's time loop on each rank's cells, 1 and 2 ranks, against the whole problem (docs/distributed.md), about 2.5 minutes"
  # cdyn run itself on each rank's cells (PT-Scotch's parts), n = 32 (the native CG path's run is (l)'s)
  $PY "$ROOT/bench/bench_mpi.py" "$BUILD/apps/cdyn" "$(command -v mpiexec)" "$ROOT" "$OUT/mpi" --sizes 32 --pcs jacobi --native "" --partitions graph
  # (OpenMPI starts as root only with the two variables, as bench_mpi.py sets them)
  for n in 16 32; do
    "$BUILD/bench/bench_subdomains" $n 16 native
    for ranks in 1 2; do
      OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec -n $ranks "$BUILD/bench/bench_subdomains" $n 16
    done
  done
fi
echo "== load average: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "== total: $(( $(date +%s) - START )) s"
