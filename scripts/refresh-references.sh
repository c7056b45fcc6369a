#!/bin/sh
# refresh-references.sh — regenerate every reference CSV in data/reference/ from the
# independent programs in reference_scripts/ (docs/verification.md: each stored reference number
# comes with the exact command that produced it).  Run from the repository root:
#     sh scripts/refresh-references.sh
# One line per CSV.  FreeFEM 4.11 (Debian freefem++): its plugins live in
# /usr/lib/freefem++, which the packaged search path misses, hence FF_LOADPATH.
set -e
cd "$(dirname "$0")/.."
FF="env FF_LOADPATH=/usr/lib/freefem++ FreeFem++ -nw -v 0"

# static membrane obstacle (FreeFEM + ff-Ipopt), read by tests/unit/test_qp_obstacle.cpp
$FF reference_scripts/static_obstacle.edp -n 10 -out data/reference/static_obstacle_n10.csv
$FF reference_scripts/static_obstacle.edp -n 20 -out data/reference/static_obstacle_n20.csv

# dynamic membrane step by step (FreeFEM + ff-Ipopt), compared live by tests/reference
for pair in P1 P1b; do
  for scheme in backward_euler midpoint; do
    $FF reference_scripts/dynamic_membrane.edp -pair $pair -scheme $scheme -n 10 -dt 0.001 -steps 300 \
        -out data/reference/dynamic_membrane_${pair}_${scheme}.csv
  done
done

# basis-independent matrix invariants (FreeFEM), read by tests/unit/test_reference_matrices.cpp
$FF reference_scripts/matrices.edp -n 4 -out data/reference/matrices_n4.csv
$FF reference_scripts/matrices.edp -n 10 -out data/reference/matrices_n10.csv

# the same invariants by GetFEM (python3-getfem)
/usr/bin/python3 reference_scripts/getfem_matrices.py -n 4 -out data/reference/getfem_matrices_n4.csv
/usr/bin/python3 reference_scripts/getfem_matrices.py -n 10 -out data/reference/getfem_matrices_n10.csv
