#!/usr/bin/env bash
# Speed of the full GMS scheme (issue 10): SI rings, 1e5 and 1e6 square lattices, one core; split and bandwidth ratio
# (about 4 min). Run after gms-rings (its SI runs give the builds per step of a whole collision).
set -euo pipefail
"$1/gms_step_benchmark" --benchmark_out="$2/benchmark.json" --benchmark_out_format=json
"${PYTHON:-/usr/bin/python3}" benchmarks/relative_executable.py "$2/benchmark.json"
"${PYTHON:-/usr/bin/python3}" benchmarks/gms_step_report.py "$2/benchmark.json" "$2/benchmark.md" \
  --rings-runs results/gms-rings/runs.csv
