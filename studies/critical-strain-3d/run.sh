#!/usr/bin/env bash
# 3D critical strain of cubic lattices (results/critical-strain-3d): the cases one per process, then the repeat runs
# that measure the machine's timing spread, appended to results.csv (about 20 min on 2 cores, 7.4 GB at 100^3).
# Called by scripts/main.sh as run.sh BIN_DIR OUT_DIR.
set -euo pipefail
py=${PYTHON:-/usr/bin/python3}
"$py" benchmarks/lattice_lobpcg_3d_report.py "$1/lattice_lobpcg_benchmark" "$2"
"$py" benchmarks/lattice_lobpcg_3d_report.py "$1/lattice_lobpcg_benchmark" "$2" --append-repeats
