#!/usr/bin/env bash
# Speed of the full GMS scheme (issue 10): SI rings, 1e5 and 1e6 square lattices, one core; split and bandwidth ratio
# (about 4 min). Run after gms-rings (its SI runs give the builds per step of a whole collision).
set -euo pipefail
# Random interleaving: the repetitions of all benchmarks in a random order instead of one benchmark's back to back, so
# that a slow spell of the shared host (this machine's speed changes by tens of per cent for minutes) falls on several
# benchmarks' repetitions rather than on every repetition of one; each ratio then compares best-of times from the
# same spread of conditions.
"$1/gms_step_benchmark" --benchmark_enable_random_interleaving=true --benchmark_out="$2/benchmark.json" \
  --benchmark_out_format=json
"${PYTHON:-/usr/bin/python3}" benchmarks/relative_executable.py "$2/benchmark.json"
"${PYTHON:-/usr/bin/python3}" benchmarks/gms_step_report.py "$2/benchmark.json" "$2/benchmark.md" \
  --rings-runs results/gms-rings/runs.csv
