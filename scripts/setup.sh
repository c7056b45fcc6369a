#!/usr/bin/env bash
# scripts/setup.sh — install every Debian package cdyn needs, then configure and
# build into build/.  Idempotent: packages already present are not reinstalled,
# and the build is incremental.  Runs as root on a fresh Debian 12 machine
# (uses sudo when not root).
set -euo pipefail
cd "$(dirname "$0")/.."

# What each package is for (see docs/dependencies.md):
packages=(
  build-essential cmake pkg-config git     # toolchain
  libeigen3-dev                            # sparse/dense linear algebra
  libsuitesparse-dev                       # CHOLMOD, UMFPACK
  libopenblas0-pthread                     # tuned BLAS under CHOLMOD's supernodal factorization
  coinor-libipopt-dev                      # Ipopt 3.11 (MUMPS inside)
  libnlopt-dev libnlopt-cxx-dev            # NLopt
  libgmsh-dev gmsh                         # gmsh C++ API and the gmsh program
  libtomlplusplus-dev                      # scene files
  libmuparser-dev                          # expressions in x, y, t
  libcli11-dev                             # command line
  nlohmann-json3-dev                       # summary.json
  libgtest-dev libgmock-dev googletest     # unit tests
  libbenchmark-dev                         # bench/
  python3 python3-matplotlib python3-meshio python3-numpy python3-getfem  # plots, VTU check, GetFEM reference
  freefem++ libfreefem++                   # independent reference numbers
)

scripts/install_missing.sh setup "${packages[@]}"

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" >/dev/null
cmake --build build -j"$jobs"
