#!/usr/bin/env bash
# scripts/setup.sh — install every Debian package cdyn needs, configure and build
# into build/, and install the Python module for /usr/bin/python3.  Idempotent:
# packages already present are not reinstalled, and the build is incremental.  Runs as
# root on a fresh Debian 12 machine (uses sudo when not root).
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
  pybind11-dev python3-pybind11 python3-dev python3-scipy  # the Python module cdyn (docs/python.md)
  python3-pytest python3-nbconvert python3-ipykernel       # its tests and notebooks (label python)
  freefem++ libfreefem++                   # independent reference numbers
  petsc-dev libopenmpi-dev openmpi-bin     # the PETSc back end under mpirun (docs/distributed.md)
  libmumps-dev libscalapack-openmpi-dev    # its parallel MUMPS, named first in the plugin's link
)

scripts/install_missing.sh setup "${packages[@]}"

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" >/dev/null
cmake --build build -j"$jobs"

# The Python module where Debian's /usr/bin/python3 finds it (PREFIX/lib/python3.X/
# dist-packages, PREFIX = /usr/local): `import cdyn` from anywhere (docs/python.md).
if [ -f build/python/cdyn/__init__.py ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
  $SUDO cmake --install build --component python >/dev/null
  echo "setup: the Python module cdyn is installed for /usr/bin/python3"
fi
