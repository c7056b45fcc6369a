#!/usr/bin/env bash
# sanitize.sh — the unit suite under AddressSanitizer + UndefinedBehaviorSanitizer
# (docs/stability.md, "Sanitizers").  Configures a separate build directory with -DCDYN_SANITIZE=ON (the top
# CMakeLists adds -fsanitize=address,undefined -fno-sanitize-recover=all: the first
# finding aborts the test that hit it, so a green run means no finding), builds the
# unit-test executables only, and runs `ctest -L unit`.
#
# Usage: scripts/sanitize.sh [BUILD_DIR] [extra ctest arguments...]
#   BUILD_DIR defaults to build-asan (next to this script's repository root).
#   JOBS (env) sets the build parallelism (default: nproc); NICE (env) its niceness.
# -O1 keeps the build time and the sanitized run time reasonable while keeping the
# stack traces usable (the sanitizers' own recommendation); Eigen's assertions stay
# on (no NDEBUG), so out-of-range indexing is caught too.  A full build takes ~20 min
# on 2 cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-asan}
shift || true
jobs=${JOBS:-$(nproc)}
nice_level=${NICE:-0}

cmake -S "$root" -B "$build" -DCDYN_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
      -DCDYN_EXAMPLES=OFF >/dev/null

# The unit tests: one executable per tests/unit/test_*.cpp (tests/CMakeLists.txt),
# plus those of tests/robustness labelled unit (when that directory is built).
targets=()
for src in "$root"/tests/unit/test_*.cpp; do targets+=("$(basename "$src" .cpp)"); done
if grep -qs "add_subdirectory(robustness)" "$root/tests/CMakeLists.txt"; then
  for src in "$root"/tests/robustness/test_*.cpp; do targets+=("$(basename "$src" .cpp)"); done
fi
nice -n "$nice_level" cmake --build "$build" -j "$jobs" --target "${targets[@]}"

# ASan's leak checker needs ptrace, which some sandboxes forbid: keep it on where it
# works (LSAN is on by default with ASan on Linux); UBSan prints a stack per finding.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1}
# gmsh 4.8 leaks a few bytes of its own (scripts/lsan.supp); cdyn's code is not suppressed.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/scripts/lsan.supp}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
cd "$build"
ctest -L unit --output-on-failure "$@"
