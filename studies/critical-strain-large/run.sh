#!/usr/bin/env bash
# Large-lattice critical strain (results/critical-strain-large): the block LOBPCG cases one per process, then SciPy's
# eigsh shift-invert against them in the same run, then summary.md with that section (about 25 min on 2 cores).
# Called by scripts/main.sh as run.sh BIN_DIR OUT_DIR. Waiting OpenMP threads sleep (passive): on a shared machine a
# spinning thread stalls its descheduled partner (critical-strain-3d/run.sh).
set -euo pipefail
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
py=${PYTHON:-/usr/bin/python3}
"$py" benchmarks/lattice_lobpcg_report.py "$1/lattice_lobpcg_benchmark" "$2"
"$py" benchmarks/scipy_eigsh_compare.py "$1" "$2"
"$py" benchmarks/lattice_lobpcg_report.py "$1/lattice_lobpcg_benchmark" "$2" --summary-only
