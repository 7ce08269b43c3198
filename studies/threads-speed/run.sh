#!/usr/bin/env bash
# Two threads against one as a user runs them (issue 35, item 2): `sphstab --threads 1|2` on the SI rings and a 10^5
# lattice, idle and beside a CPU-bound process, under three OpenMP wait policies, with the machine's two-process
# throughput in the same run (about 6 min). Called by scripts/main.sh as run.sh BIN_DIR OUT_DIR.
set -euo pipefail
"${PYTHON:-/usr/bin/python3}" benchmarks/threads_report.py "$1" "$2"
