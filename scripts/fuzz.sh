#!/usr/bin/env bash
# fuzz.sh — build the libFuzzer targets of fuzz/ with clang (ASan + UBSan, coverage of
# the whole project) and run each for a bounded time (docs/stability.md, "Fuzzing").
#
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#   SECONDS_PER_TARGET  default 60 (env FUZZ_SECONDS also works)
#   TARGET              scene, expression, mesh (default: all three)
# Env: BUILD_DIR (default build-fuzz), JOBS (build parallelism, default nproc),
#      CORPUS_DIR (default BUILD_DIR/corpus: grows between runs; the seeds are copied in).
# Needs clang++ and the libFuzzer runtime (Debian: clang, libclang-rt-14-dev).
#
# A crash, sanitizer report, timeout or out-of-memory stops that target and leaves its
# input as BUILD_DIR/findings/<target>/crash-* (or timeout-*, oom-*); the script then
# exits 1.  Keep such an input under tests/robustness/regressions/<target>/ once fixed:
# the CTest robustness_regressions replays every file there through the same entry
# function (fuzz/entries.hpp) in the ordinary gcc build.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-${FUZZ_SECONDS:-60}}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene expression mesh)
build=${BUILD_DIR:-$root/build-fuzz}
jobs=${JOBS:-$(nproc)}
corpus_root=${CORPUS_DIR:-$build/corpus}

# clang and its libFuzzer runtime are not needed by the build or the tests, so
# scripts/setup.sh leaves them out; this script installs them when missing (Debian 12).
"$root/scripts/install_missing.sh" fuzz.sh clang libclang-rt-14-dev
# (No OpenMP: clang's runtime is another package, libomp-dev, and the fuzzed parsers do
# not thread; the kernel's loops then run on one thread, with the same results.)
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
      -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" \
      -DCDYN_SANITIZE=ON -DCDYN_FUZZ=ON -DCDYN_EXAMPLES=OFF -DCDYN_WITH_OPENMP=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target "${targets[@]/#/fuzz_}"

# Seed corpora: the shipped scenes, the expressions found in them, and the small
# .msh files of fuzz/seeds (2.2 and 4.1, written by gmsh from a square and bar.geo).
seed() {  # seed TARGET: fills $corpus_root/TARGET
  local dir=$corpus_root/$1
  mkdir -p "$dir"
  case $1 in
    scene)
      cp "$root"/data/scenes/*.toml "$dir"/
      ;;
    expression)
      grep -hoE '= *"[^"]*"' "$root"/data/scenes/*.toml | sed -E 's/^= *"(.*)"$/\1/' | sort -u |
        while IFS= read -r e; do printf '%s' "$e" > "$dir/seed_$(printf '%s' "$e" | md5sum | cut -c1-12)"; done
      printf '%s' '0.02*sin(pi*x)*(t<0.5)' > "$dir/seed_doc"
      printf '%s' 'x>0.5 ? min(x,y) : max(abs(x-1),sqrt(y))' > "$dir/seed_ternary"
      ;;
    mesh)
      cp "$root"/fuzz/seeds/*.msh "$dir"/
      ;;
  esac
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
for t in "${targets[@]}"; do
  seed "$t"
  findings=$build/findings/$t
  mkdir -p "$findings"
  echo "== fuzz_$t: $seconds s, corpus $corpus_root/$t"
  # -max_len: scenes and meshes of interest are small; -timeout: one input taking
  # longer than 10 s is a finding (a hang); -rss_limit_mb: a runaway allocation is one.
  if ! "$build/fuzz/fuzz_$t" "$corpus_root/$t" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
       -rss_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 2>"$build/findings/$t.log"; then
    echo "fuzz_$t: FINDING, see $build/findings/$t.log and $findings/" >&2
    grep -E "ERROR|runtime error|==[0-9]+==|Test unit written" "$build/findings/$t.log" | head -5 >&2 || true
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb|cov: " "$build/findings/$t.log" | tail -3
  fi
done
exit $status
