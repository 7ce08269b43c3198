#!/usr/bin/env bash
# 3D critical strain of cubic lattices (results/critical-strain-3d): the cases one per process, then the repeat runs
# that measure the machine's timing spread, appended to results.csv (8 min on 2 cores beside other jobs, 1.2 GB at
# 100^3 by offset, 2.0 GB for the per-pair n = 64). Called by scripts/main.sh as run.sh BIN_DIR OUT_DIR. Waiting
# OpenMP threads sleep (passive): on a shared machine a spinning thread stalls its descheduled partner (5x at n = 16).
set -euo pipefail
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
py=${PYTHON:-/usr/bin/python3}
"$py" benchmarks/lattice_lobpcg_3d_report.py "$1/lattice_lobpcg_benchmark" "$2"
"$py" benchmarks/lattice_lobpcg_3d_report.py "$1/lattice_lobpcg_benchmark" "$2" --append-repeats
