#!/usr/bin/env bash
# Speed of the finite-strain total-Lagrangian step (issue 11): 1e4, 1e5 and 1e6 particles, one core, against the triad
# bandwidth measured in the same run (about 1.5 min, peak 3.1 GB).
set -euo pipefail
"$1/tl_step_benchmark" --benchmark_out="$2/benchmark.json" --benchmark_out_format=json
"${PYTHON:-/usr/bin/python3}" benchmarks/relative_executable.py "$2/benchmark.json"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
"${PYTHON:-/usr/bin/python3}" benchmarks/tl_step_report.py "$2/benchmark.json" "$2/benchmark.md" --commit "$commit"
