#!/usr/bin/env bash
# scripts/test.sh — the project's test command: set up (install packages, configure,
# build) when needed, then run the whole CTest suite.  Extra arguments go to ctest,
# e.g. `scripts/test.sh -L unit`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
# ctest runs as many tests at once as there are cores: each on one thread (OpenMP's
# default would give each all the cores, and threads that wait on each other across
# oversubscribed cores make a run many times slower).  The thread tests set their own
# counts (solver.threads, set_thread_count) and run alone.
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
ctest --test-dir build --output-on-failure -j"$jobs" "$@"
