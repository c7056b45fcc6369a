#!/usr/bin/env bash
# scripts/test.sh — the project's test command: set up (install packages, configure,
# build) when needed, then run the whole CTest suite.  Extra arguments go to ctest,
# e.g. `scripts/test.sh -L unit`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs" "$@"
